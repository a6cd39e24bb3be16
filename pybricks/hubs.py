"""The EV3 brick itself: EV3Brick (pybricks.hubs, Pybricks 2.0).

pybricks-micropython v2.0.0, extmod/modhubs.c (hubs_EV3Brick_make_new): an EV3Brick has `screen` (an
Image of the screen, media.ev3dev), `speaker` (the one Speaker), `light` (the status light), and the
modules `buttons` and `battery` as class attributes (extmod/modbuttons.c, extmod/modbattery.c).
"""

from . import _link
from ._image import Image
from ._speaker import Speaker
from .parameters import Button, Color

__all__ = ["EV3Brick"]

# lib/pbio/drv/button/button_linux_ev3.c: the EV3's keys; modbuttons.c lists them in this order
_BUTTONS = (("enter", Button.CENTER), ("left", Button.LEFT), ("right", Button.RIGHT), ("up", Button.UP))
_BUTTONS += (("down", Button.DOWN), ("backspace", Button.LEFT_UP))

# lib/pbio/drv/ev3dev_stretch/light.c: the LEDs, red ones first, and the red and green for each colour
_LEDS = (
    "led0:red:brick-status",
    "led1:red:brick-status",
    "led0:green:brick-status",
    "led1:green:brick-status",
)
_LIGHT_RG = {"RED": (255, 0), "ORANGE": (255, 255), "YELLOW": (30, 255), "GREEN": (0, 255)}

_BATTERY = "lego-ev3-battery"


class _Buttons:
    """The brick's buttons (the `buttons` module of the firmware)."""

    __name__ = "buttons"

    @staticmethod
    def pressed():
        """The buttons pressed now, a list of Button members (CENTER, LEFT, RIGHT, UP, DOWN, LEFT_UP for
        the back button), in that order."""
        down = set(_link.call("buttons"))
        return [button for name, button in _BUTTONS if name in down]

    def __repr__(self):
        return "<module 'buttons'>"


class _Battery:
    """The brick's battery (the `battery` module of the firmware, lib/pbio/drv/battery/
    battery_linux_ev3.c)."""

    __name__ = "battery"

    @staticmethod
    def voltage():
        """The battery's voltage in mV."""
        return int(int(_link.read("power_supply", _BATTERY, "voltage_now")) / 1000) & 0xFFFF

    @staticmethod
    def current():
        """The current the battery gives, in mA."""
        return int(int(_link.read("power_supply", _BATTERY, "current_now")) / 1000) & 0xFFFF

    def __repr__(self):
        return "<module 'battery'>"


class _ColorLight:
    """The brick's status light: on(color) and off() (extmod/modbuiltins.c ColorLight)."""

    def on(self, color, brightness=100):
        """Light in `color`: RED, ORANGE, YELLOW and GREEN show (the EV3's LEDs are red and green); any
        other Color, or None, is off.  Brightness other than 100 is not implemented, as on the brick."""
        if color is None:
            color = Color.BLACK
        if getattr(color, "_enum", None) != "Color":
            raise TypeError(f"Expected Color, got {type(color).__name__}")
        if isinstance(brightness, float):
            brightness = int(brightness)
        if not isinstance(brightness, int):
            raise TypeError(f"can't convert {type(brightness).__name__} to int")
        if max(0, min(100, brightness)) != 100:
            raise NotImplementedError
        red, green = _LIGHT_RG.get(color.name, (0, 0))
        for index, led in enumerate(_LEDS):
            _link.write("leds", led, "brightness", str(red if index < 2 else green))

    def off(self):
        """Turn the light off."""
        self.on(Color.BLACK)

    def __repr__(self):
        return "<ColorLight>"


class EV3Brick:
    """The LEGO MINDSTORMS EV3 brick: its buttons, light, speaker, screen and battery."""

    buttons = _Buttons()
    battery = _Battery()

    def __init__(self):
        self.screen = Image("_screen_")
        self.speaker = Speaker()
        self.light = _ColorLight()
