"""EV3 MicroPython 1.0's brick module (pybricks.ev3brick, kept in Pybricks 2.0 for 1.0 programs).

pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/ev3brick.py: `sound` (a 1.0 Speaker),
`display` (a 1.0 Display, which clears the screen when the module is imported), `battery` (the 2.0
EV3Brick's), `light(color)` and `buttons()`.
"""

from .display import Display
from .hubs import EV3Brick
from .speaker import Speaker

_brickobj = EV3Brick()

sound = Speaker("EV3")
display = Display("EV3")

battery = _brickobj.battery


def light(color):
    """Light the status light in `color` (Color.RED, ORANGE, YELLOW, GREEN; None or another is off)."""
    _brickobj.light.on(color)


def buttons():
    """The buttons pressed now, a list of Button members."""
    return _brickobj.buttons.pressed()
