"""EV3 gyro sensor: angle and rate of turn, clockwise positive, as the EV3 driver reports them.

The angle is counted from the robot's heading at power-on (or the last reset)
and is not wrapped: two turns to the right read 720.  As on the EV3 gyro,
changing the mode (to any other mode, GYRO-RATE and back to GYRO-ANG say)
resets the angle to 0, and writing the mode it is already in does not
(ev3dev/ev3dev#402, ev3dev/ev3dev-lang-python#517); so does the reset command
(0x11 written to `direct`).  The modes are in the driver's order
(lego-linux-drivers sensors/ev3_uart_sensor_defs.c, LEGO_EV3_GYRO).
"""

from __future__ import annotations

import math

from .device import invalid
from .sensor import LegoSensor, Mode


class GyroSensor(LegoSensor):
    KIND = "gyro"
    DRIVER = "lego-ev3-gyro"
    FACINGS = ("down", "forward")  # it measures the robot's turns, whichever way it is fitted
    MODES = {
        "GYRO-ANG": Mode(1, 0, "deg", "s16", -32768, 32767),
        "GYRO-RATE": Mode(1, 0, "d/s", "s16", -440, 440),
        "GYRO-FAS": Mode(1, 0, "", "s16", -1464, 1535),
        "GYRO-G&A": Mode(2, 0, "", "s16", -32768, 32767),
        "GYRO-CAL": Mode(4, 0, "", "s16", -32768, 32767, noisy=False),
        "TILT-RATE": Mode(1, 0, "d/s", "s16", -440, 440),
        "TILT-ANG": Mode(1, 0, "deg", "s16", -32768, 32767),
    }

    def __init__(self, address, spec, surroundings) -> None:
        super().__init__(address, spec, surroundings)
        self.zero_rad = surroundings.heading_rad
        self.writers["direct"] = self._direct

    def _direct(self, value: str) -> None:
        if value != "\x11":  # the byte 0x11, as the brick sends bytes (decoded as latin-1)
            raise invalid(value)
        self.reset()

    def reset(self) -> None:
        self.zero_rad = self.around.heading_rad
        self._sample_tick = -1  # a sample taken this tick before the reset is out of date

    def mode_changed(self) -> None:
        self.reset()

    def measure(self, mode: str) -> tuple[float, ...]:
        angle = -math.degrees(self.around.heading_rad - self.zero_rad)
        rate = -math.degrees(self.around.turn_rate)
        if mode == "GYRO-ANG":
            return (angle,)
        if mode in ("GYRO-RATE", "GYRO-FAS"):
            return (rate,)
        if mode == "GYRO-G&A":
            return (angle, rate)
        if mode == "GYRO-CAL":
            return (0, 0, 0, 0)
        return (0,)  # no tilt in a flat world
