"""NXT sound sensor: the sound level around the robot, in tenths of a percent.

The simulated room is quiet (5 %); the robot's own speaker, while it plays,
is loud (60 %) to its own sound sensor.  As the lego-nxt-sound driver gives
them (lego-linux-drivers sensors/nxt_analog_sensor_defs.c): DB and DBA, one
value with one decimal, bin_data in s32 holding the unscaled reading in
millivolts (0 to 5000 for 0 to 100 %).
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

QUIET_PCT = 5.0
SPEAKER_PCT = 60.0


class NxtSoundSensor(LegoSensor):
    DRIVER = "lego-nxt-sound"
    MODES = {
        "DB": Mode(1, 1, "pct", "s32", 0, 1000, raw=(0, 5000, 0, 1000)),
        "DBA": Mode(1, 1, "pct", "s32", 0, 1000, raw=(0, 5000, 0, 1000)),
    }

    def measure(self, mode: str) -> tuple[float, ...]:
        playing = self.around.sound_until_tick > self.around.tick
        return (SPEAKER_PCT if playing else QUIET_PCT,)
