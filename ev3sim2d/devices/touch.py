"""EV3 touch sensor: pressed while its bumper touches a wall or another robot.

The bumper is a segment `bumper_cm` wide (robot file option; 2 cm by default, the sensor's own
button) across the direction the sensor faces, at its tip: a wall anywhere along it presses it,
so a robot that meets a wall at an angle presses its bumper as soon as the bumper's corner meets
the wall.  The bumper is part of the robot's footprint (robot.body_outline), so the wall stops the
robot there.  A wall that only grazes the bumper's end from the side (a robot sliding along a
wall) does not press it: the last SIDE_CM of each end count only for walls in front.
"""

from __future__ import annotations

import math

from .sensor import LegoSensor, Mode

REACH_CM = 0.6  # how close a wall must come to the bumper to press it
AHEAD_CM = 0.3  # the bumper's face lies this far ahead of the sensor's position
SIDE_CM = 0.8  # each end of the bumper presses only from the front (not for a wall along the side)
DEFAULT_BUMPER_CM = 2.0


class TouchSensor(LegoSensor):
    KIND = "touch"
    DRIVER = "lego-ev3-touch"
    MODES = {
        "TOUCH": Mode(1, 0, "", "s32", 0, 1, noisy=False)
    }  # (lego-linux-drivers sensors/ev3_analog_sensor_defs.c)
    FACINGS = ("forward",)
    FACING_HINTS = {
        "down": "a touch sensor facing down would be pressed by the floor all the time; write `facing: forward`"
    }
    OPTIONS = {
        "bumper_cm": (
            DEFAULT_BUMPER_CM,
            "cm",
            "bumper width across its tip: a wall anywhere on it presses it",
        )
    }
    HOUSING = "bumper"

    def __init__(self, address, spec, surroundings) -> None:
        super().__init__(address, spec, surroundings)
        width = float(spec.options.get("bumper_cm", DEFAULT_BUMPER_CM))
        self.half = max(width / 2 - SIDE_CM, 0.0)  # half the part of the bumper a wall may press

    def pressed(self) -> bool:
        x, y, facing = self.position()
        cos, sin = math.cos(facing), math.sin(facing)
        x, y = x + AHEAD_CM * cos, y + AHEAD_CM * sin
        if self.half == 0.0:
            return self.around.near(x, y, REACH_CM)
        dx, dy = -self.half * sin, self.half * cos
        return self.around.touches_segment(x - dx, y - dy, x + dx, y + dy, REACH_CM)

    def measure(self, mode: str) -> tuple[float, ...]:
        return (1 if self.pressed() else 0,)
