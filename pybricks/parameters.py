"""Constant parameters: Port, Direction, Stop, Color, Button, Align (pybricks.parameters, Pybricks 2.0).

In the firmware these are enums written in C (extmod/modparameters.c): each member is an object of its
enum's type, printed as `Color.RED`, equal only to itself, usable as a dict key; the enum type itself
cannot be made.  `Align` is a plain class of ints (bricks/ev3dev/modules/pybricks/parameters.py), and
`SoundFile` and `ImageFile` are here too, as EV3 MicroPython 1.0 had them.
"""


class _Member:
    """One member of an enum: its enum's name, its own name, the firmware's value."""

    __slots__ = ("_enum", "name", "_value")

    def __init__(self, enum, name, value):
        self._enum = enum
        self.name = name
        self._value = value

    def __repr__(self):
        return self._enum + "." + self.name

    __str__ = __repr__

    def __hash__(self):
        return hash((self._enum, self.name))

    def __reduce__(self):
        return (getattr, (_ENUMS[self._enum], self.name))


_ENUMS = {}


class _EnumType(type):
    """An enum as the firmware has them: iterating one is not possible, and it cannot be called."""

    def __call__(cls, *args, **kwargs):
        raise TypeError(f"cannot create '{cls.__name__}' instances")

    def __repr__(cls):
        return f"<class '{cls.__name__}'>"


def _enum(name, members):
    namespace = {"__module__": __name__, "__doc__": f"The {name} constants (pybricks.parameters.{name})."}
    enum = _EnumType(name, (), namespace)
    for member, value in members:
        setattr(enum, member, _Member(name, member, value))
    _ENUMS[name] = enum
    return enum


# extmod/modparameters.c, pb_enum_Port_table (an EV3 has A-D and S1-S4; E and F are other hubs')
Port = _enum(
    "Port", [("A", 65), ("B", 66), ("C", 67), ("D", 68), ("S1", 49), ("S2", 50), ("S3", 51), ("S4", 52)]
)
Direction = _enum("Direction", [("CLOCKWISE", 0), ("COUNTERCLOCKWISE", 1)])
Stop = _enum("Stop", [("COAST", 0), ("BRAKE", 1), ("HOLD", 2)])
# pb_Color_enum_table, in its order
Color = _enum(
    "Color",
    [
        ("BLACK", 1),
        ("PURPLE", 2),
        ("BLUE", 3),
        ("GREEN", 4),
        ("YELLOW", 5),
        ("ORANGE", 6),
        ("RED", 7),
        ("WHITE", 8),
        ("BROWN", 9),
    ],
)
Button = _enum(
    "Button",
    [
        ("UP", 1),
        ("DOWN", 2),
        ("LEFT", 3),
        ("RIGHT", 4),
        ("CENTER", 5),
        ("LEFT_UP", 6),
        ("LEFT_DOWN", 7),
        ("RIGHT_UP", 8),
        ("RIGHT_DOWN", 9),
    ],
)
Button.BEACON = Button.UP  # (the firmware's BEACON is the member with UP's value)


class Align:
    """Where an image goes on the screen (EV3 MicroPython 1.0's Display.image)."""

    BOTTOM_LEFT = 1
    BOTTOM = 2
    BOTTOM_RIGHT = 3
    LEFT = 4
    CENTER = 5
    RIGHT = 6
    TOP_LEFT = 7
    TOP = 8
    TOP_RIGHT = 9


from ._media_files import ImageFile, SoundFile  # noqa: E402, F401 - 1.0 programs import them from here
