"""
Wheels and rims, for turning distances into rotations (python-ev3dev2 2.1.0).

A great reference when adding new wheels is http://wheels.sariel.pl/
"""

from math import pi


class Wheel:
    """
    A wheel, tire, etc.; all units are mm.

    Example: ``rotations_for_500mm = 500 / EV3Tire().circumference_mm``
    """

    def __init__(self, diameter_mm, width_mm):
        self.diameter_mm = float(diameter_mm)
        self.width_mm = float(width_mm)
        self.circumference_mm = diameter_mm * pi

    @property
    def radius_mm(self):
        return float(self.diameter_mm / 2)


class EV3Rim(Wheel):
    """Part number 56145, comes in set 31313."""

    def __init__(self):
        Wheel.__init__(self, 30, 20)


class EV3Tire(Wheel):
    """Part number 44309, comes in set 31313."""

    def __init__(self):
        Wheel.__init__(self, 43.2, 21)


class EV3EducationSetRim(Wheel):
    """Part number 56908, comes in set 45544."""

    def __init__(self):
        Wheel.__init__(self, 43, 26)


class EV3EducationSetTire(Wheel):
    """Part number 41897, comes in set 45544."""

    def __init__(self):
        Wheel.__init__(self, 56, 28)
