"""EV3 ultrasonic sensor facing forward: distance to the nearest wall or robot in a narrow cone.

Three rays (the cone's edges and its axis, `cone_deg` wide, default 15°) from
the sensor; the shortest hit wins.  0 to 255 cm; 255 cm when nothing is in range.
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

RANGE_CM = 255.0
DEFAULT_CONE_DEG = 15.0


class UltrasonicSensor(LegoSensor):
    DRIVER = "lego-ev3-us"
    MODES = {
        "US-DIST-CM": Mode(1, 1, "cm", "u16", 0, 2550),
        "US-DIST-IN": Mode(1, 1, "in", "u16", 0, 1003),
        "US-LISTEN": Mode(1, 0, "", "u8", 0, 1, noisy=False),
        "US-SI-CM": Mode(1, 1, "cm", "u16", 0, 2550),
        "US-SI-IN": Mode(1, 1, "in", "u16", 0, 1003),
        "US-DC-CM": Mode(1, 1, "cm", "u16", 0, 2550),
        "US-DC-IN": Mode(1, 1, "in", "u16", 0, 1003),
    }

    def __init__(self, address, spec, surroundings) -> None:
        super().__init__(address, spec, surroundings)
        self.cone_deg = float(spec.options.get("cone_deg", DEFAULT_CONE_DEG))
        self.range_cm = float(spec.options.get("max_cm", RANGE_CM))

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "US-LISTEN":
            return (0,)
        d = self.nearest_in_cone(self.cone_deg, self.range_cm)
        return (d / 2.54,) if mode.endswith("-IN") else (d,)
