"""Distances in several units, all convertible to millimeters (python-ev3dev2 2.1.0)."""

import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)

CENTIMETER_MM = 10
DECIMETER_MM = 100
METER_MM = 1000
INCH_MM = 25.4
FOOT_MM = 304.8
YARD_MM = 914.4
STUD_MM = 8


class DistanceValue:
    """
    Base class of the distance units; use :class:`DistanceMillimeters`, :class:`DistanceCentimeters`,
    :class:`DistanceDecimeters`, :class:`DistanceMeters`, :class:`DistanceInches`, :class:`DistanceFeet`,
    :class:`DistanceYards` or :class:`DistanceStuds`.
    """

    # This allows us to sort lists of DistanceValue objects
    def __lt__(self, other):
        return self.mm < other.mm

    def __rmul__(self, other):
        return self.__mul__(other)


class DistanceMillimeters(DistanceValue):
    """Distance in millimeters."""

    def __init__(self, millimeters):
        self.millimeters = millimeters

    def __str__(self):
        return str(self.millimeters) + "mm"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceMillimeters(self.millimeters * other)

    @property
    def mm(self):
        return self.millimeters


class DistanceCentimeters(DistanceValue):
    """Distance in centimeters."""

    def __init__(self, centimeters):
        self.centimeters = centimeters

    def __str__(self):
        return str(self.centimeters) + "cm"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceCentimeters(self.centimeters * other)

    @property
    def mm(self):
        return self.centimeters * CENTIMETER_MM


class DistanceDecimeters(DistanceValue):
    """Distance in decimeters."""

    def __init__(self, decimeters):
        self.decimeters = decimeters

    def __str__(self):
        return str(self.decimeters) + "dm"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceDecimeters(self.decimeters * other)

    @property
    def mm(self):
        return self.decimeters * DECIMETER_MM


class DistanceMeters(DistanceValue):
    """Distance in meters."""

    def __init__(self, meters):
        self.meters = meters

    def __str__(self):
        return str(self.meters) + "m"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceMeters(self.meters * other)

    @property
    def mm(self):
        return self.meters * METER_MM


class DistanceInches(DistanceValue):
    """Distance in inches."""

    def __init__(self, inches):
        self.inches = inches

    def __str__(self):
        return str(self.inches) + "in"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceInches(self.inches * other)

    @property
    def mm(self):
        return self.inches * INCH_MM


class DistanceFeet(DistanceValue):
    """Distance in feet."""

    def __init__(self, feet):
        self.feet = feet

    def __str__(self):
        return str(self.feet) + "ft"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceFeet(self.feet * other)

    @property
    def mm(self):
        return self.feet * FOOT_MM


class DistanceYards(DistanceValue):
    """Distance in yards."""

    def __init__(self, yards):
        self.yards = yards

    def __str__(self):
        return str(self.yards) + "yd"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceYards(self.yards * other)

    @property
    def mm(self):
        return self.yards * YARD_MM


class DistanceStuds(DistanceValue):
    """Distance in studs (8 mm each)."""

    def __init__(self, studs):
        self.studs = studs

    def __str__(self):
        return str(self.studs) + "stud"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return DistanceStuds(self.studs * other)

    @property
    def mm(self):
        return self.studs * STUD_MM
