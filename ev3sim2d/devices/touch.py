"""EV3 touch sensor: pressed while its bumper tip touches a wall or another robot."""

from __future__ import annotations

import math

from .sensor import LegoSensor, Mode

REACH_CM = 0.6  # how close a wall must come to the bumper tip to press it


class TouchSensor(LegoSensor):
    DRIVER = "lego-ev3-touch"
    MODES = {"TOUCH": Mode(1, 0, "", "s8", 0, 1, noisy=False)}

    def pressed(self) -> bool:
        x, y, facing = self.position()
        return self.around.near(x + 0.3 * math.cos(facing), y + 0.3 * math.sin(facing), REACH_CM)

    def measure(self, mode: str) -> tuple[float, ...]:
        return (1 if self.pressed() else 0,)
