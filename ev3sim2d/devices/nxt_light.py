"""NXT light sensor facing down: reflected light (red LED on) or ambient light, in tenths of a percent.

It sees a floor spot like the EV3 colour sensor (default 2 cm) but reads a
narrower range, as the NXT sensor does: about 23 % on black tape, 61 % on
white paper (20 + 0.55 × the EV3 colour sensor's reflected value).
"""

from __future__ import annotations

from .color import ColorSensor
from .sensor import Mode


class NxtLightSensor(ColorSensor):
    DRIVER = "lego-nxt-light"
    MODES = {
        "REFLECT": Mode(1, 1, "pct", "s16", 0, 1000),
        "AMBIENT": Mode(1, 1, "pct", "s16", 0, 1000),
    }

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "AMBIENT":
            return (self.ambient,)
        (ev3_reflected,) = super().measure("COL-REFLECT")
        return (20.0 + 0.55 * ev3_reflected,)
