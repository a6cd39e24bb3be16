"""EV3 infrared sensor: proximity to the nearest wall or robot ahead (0 to 100; 100 = about 70 cm or more).

There are no beacons or remotes in the world yet: seek mode reports no
beacon (-128 distance) and remote mode no buttons (IR-REM-A: 384, the driver's
"no buttons are pressed" value).  Modes, value counts and data formats as the
driver gives them (lego-linux-drivers sensors/ev3_uart_sensor_defs.c,
LEGO_EV3_INFRARED): s8 but for IR-REM-A (s16) and IR-CAL (s32).
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

FULL_SCALE_CM = 70.0
DEFAULT_CONE_DEG = 30.0


class InfraredSensor(LegoSensor):
    KIND = "infrared"
    DRIVER = "lego-ev3-ir"
    MODES = {
        "IR-PROX": Mode(1, 0, "pct", "s8", 0, 100),
        # headings -25..25, distances 0..100 or -128 for no beacon (the driver's @value0..7)
        "IR-SEEK": Mode(8, 0, "pct", "s8", -128, 100, noisy=False),
        "IR-REMOTE": Mode(4, 0, "btn", "s8", 0, 11, noisy=False),
        "IR-REM-A": Mode(1, 0, "", "s16", 0, 32767, noisy=False),
        "IR-S-ALT": Mode(4, 0, "pct", "s8", 0, 100, noisy=False),
        "IR-CAL": Mode(2, 0, "", "s32", 0, 1023, noisy=False),
    }
    FACINGS = ("forward",)
    FACING_HINTS = {
        "down": (
            "an infrared sensor facing down would see the floor, which ev3sim2d does not model; "
            "write `facing: forward`"
        )
    }
    OPTIONS = {
        "cone_deg": (DEFAULT_CONE_DEG, "degrees", "full opening angle of the infrared beam"),
        "max_cm": (FULL_SCALE_CM, "cm", "distance that reads as proximity 100"),
    }
    HOUSING = "eyes"
    BEAM_APPROXIMATE = True

    @classmethod
    def beam_cm(cls, mode: str, values: list[int], max_cm: float) -> float | None:
        return values[0] / 100 * max_cm if values and mode == "IR-PROX" else None

    def __init__(self, address, spec, surroundings) -> None:
        super().__init__(address, spec, surroundings)
        self.full_cm = float(spec.options.get("max_cm", FULL_SCALE_CM))
        self.cone_deg = float(spec.options.get("cone_deg", DEFAULT_CONE_DEG))

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "IR-PROX":
            return (100.0 * self.nearest_in_cone(self.cone_deg, self.full_cm) / self.full_cm,)
        if mode == "IR-SEEK":
            return (0, -128) * 4
        if mode == "IR-REM-A":
            return (384,)
        return (0,) * self.MODES[mode].num_values
