"""EV3 ultrasonic sensor facing forward: distance to the nearest wall or robot in a narrow cone.

The nearest point of a wall or another robot anywhere inside the cone (`cone_deg`
wide, default 15°, from the sensor), found exactly on every tick, so a corner
that reaches into the cone between its axis and its edges is seen as long as it
is in the cone (simulator/physics.py, Physics.cone).  0 to 255 cm; 255 cm when
nothing is in range.

US-DIST-* (and US-DC-*) measure continuously.  US-SI-CM and US-SI-IN are single
measurements, as the driver documents them: "A measurement is taken when the
mode is set and value0 will not change after this. To take another measurement
set the mode again" (lego-linux-drivers sensors/ev3_uart_sensor_defs.c,
LEGO_EV3_ULTRASONIC mode 3); writing the mode again, even the same one, pings
again.  Data formats as the driver gives them: s16 for the distances, s8 for
US-LISTEN.
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

RANGE_CM = 255.0
DEFAULT_CONE_DEG = 15.0
SINGLE = ("US-SI-CM", "US-SI-IN")


class UltrasonicSensor(LegoSensor):
    KIND = "ultrasonic"
    DRIVER = "lego-ev3-us"
    MODES = {
        "US-DIST-CM": Mode(1, 1, "cm", "s16", 0, 2550),
        "US-DIST-IN": Mode(1, 1, "in", "s16", 0, 1003),
        "US-LISTEN": Mode(1, 0, "", "s8", 0, 1, noisy=False),
        "US-SI-CM": Mode(1, 1, "cm", "s16", 0, 2550),
        "US-SI-IN": Mode(1, 1, "in", "s16", 0, 1003),
        "US-DC-CM": Mode(1, 1, "cm", "s16", 0, 2550),
        "US-DC-IN": Mode(1, 1, "in", "s16", 0, 1003),
    }
    FACINGS = ("forward",)
    FACING_HINTS = {
        "down": (
            "an ultrasonic sensor facing down would measure its height above the floor, which ev3sim2d does "
            "not model (the floor is flat and has no height); write `facing: forward`"
        )
    }
    OPTIONS = {
        "cone_deg": (DEFAULT_CONE_DEG, "degrees", "full opening angle of the sound beam"),
        "max_cm": (RANGE_CM, "cm", "farthest distance measured; beyond it the sensor reads max_cm"),
    }
    HOUSING = "eyes"

    @classmethod
    def beam_cm(cls, mode: str, values: list[int], max_cm: float) -> float | None:
        if not values or not mode.startswith(("US-DIST", "US-SI", "US-DC")):
            return None
        value = values[0] / 10
        return value * 2.54 if mode.endswith("-IN") else value

    def __init__(self, address, spec, surroundings) -> None:
        super().__init__(address, spec, surroundings)
        self.cone_deg = float(spec.options.get("cone_deg", DEFAULT_CONE_DEG))
        self.range_cm = float(spec.options.get("max_cm", RANGE_CM))
        self._ping: tuple[int, ...] | None = None  # the single measurement a US-SI-* mode holds

    def mode_selected(self) -> None:
        self._ping = None
        if self.mode in SINGLE:
            self._sample_tick = -1  # a new ping, even in the tick of the last one
            self._ping = super().values()  # measured when the mode is written

    def values(self) -> tuple[int, ...]:
        if self.mode in SINGLE:
            if self._ping is None:  # (only if a US-SI mode was the first mode, which it is not)
                self._ping = super().values()
            return self._ping
        return super().values()

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "US-LISTEN":
            return (0,)
        d = self.nearest_in_cone(self.cone_deg, self.range_cm)
        return (d / 2.54,) if mode.endswith("-IN") else (d,)
