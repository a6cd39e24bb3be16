"""NXT sound sensor: the sound level around the robot, in tenths of a percent.

The simulated room is quiet (5 %); the robot's own speaker, while it plays,
is loud (60 %) to its own sound sensor.
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

QUIET_PCT = 5.0
SPEAKER_PCT = 60.0


class NxtSoundSensor(LegoSensor):
    DRIVER = "lego-nxt-sound"
    MODES = {
        "DB": Mode(1, 1, "pct", "s16", 0, 1000),
        "DBA": Mode(1, 1, "pct", "s16", 0, 1000),
    }

    def measure(self, mode: str) -> tuple[float, ...]:
        playing = self.around.sound_until_tick > self.around.tick
        return (SPEAKER_PCT if playing else QUIET_PCT,)
