"""NXT light sensor: reflected light (red LED on) or ambient light, in tenths of a percent.

Facing down, it sees a floor spot like the EV3 colour sensor (default 2 cm) but
reads a narrower range, as the NXT sensor does: about 23 % on black tape, 61 %
on white paper (20 + 0.55 × the EV3 colour sensor's reflected value).

Facing forward (`facing: forward`), it reads a wall ahead by its distance as the
EV3 colour sensor does (see color.py: full within 1 cm, nothing from 10 cm), on
the same scale: 20 + 0.55 × the EV3 sensor's reading there, so 61 % against a
wall and 20 % (its floor-less value: the NXT sensor has no LED-off reference to
take the room's light away) with nothing in front.  The floor is not read.

As the lego-nxt-light driver gives them (lego-linux-drivers
sensors/nxt_analog_sensor_defs.c): REFLECT and AMBIENT, one value with one
decimal, and bin_data in s32 holding the unscaled reading in millivolts
(REFLECT: 4116 mV at 0 %, 543 mV at 100 %; AMBIENT: 4164 and 773).
"""

from __future__ import annotations

from .color import WALL, ColorSensor
from .sensor import Mode


class NxtLightSensor(ColorSensor):
    KIND = "nxt-light"
    DRIVER = "lego-nxt-light"
    MODES = {
        "REFLECT": Mode(1, 1, "pct", "s32", 0, 1000, raw=(4116, 543, 0, 1000)),
        "AMBIENT": Mode(1, 1, "pct", "s32", 0, 1000, raw=(4164, 773, 0, 1000)),
    }
    OPTIONS = {"spot_cm": (2.0, "cm", "diameter of the floor spot the sensor sees")}
    LABEL = "NXT light"

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "AMBIENT":
            return (self.ambient,)
        (ev3_reflected,) = super().measure("COL-REFLECT")
        return (20.0 + 0.55 * ev3_reflected,)

    def measure_forward(self, mode: str) -> tuple[float, ...]:
        if mode == "AMBIENT":
            return (self.ambient,)
        return (20.0 + 0.55 * WALL.reflected * self.wall_share(),)
