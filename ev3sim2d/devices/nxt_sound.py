"""NXT sound sensor: the sound level around the robot, in tenths of a percent.

The simulated room is quiet (5 %); the robot's own speaker, while it plays,
is loud (60 %) to its own sound sensor.  Other robots' speakers add by the
inverse square of the distance (robot.py, Robot.sound_level: 60 % x volume at
10 cm or nearer, 15 % at 20 cm, 0.6 % at 1 m).  As the lego-nxt-sound driver gives
them (lego-linux-drivers sensors/nxt_analog_sensor_defs.c): DB and DBA, one
value with one decimal, bin_data in s32 holding the unscaled reading in
millivolts (0 to 5000 for 0 to 100 %).
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

QUIET_PCT = 5.0
SPEAKER_PCT = 60.0  # the robot's own speaker, a few cm from its sensor
# another robot's speaker at volume V % heard d cm away: SPEAKER_PCT * V/100 * (SOUND_REF_CM / d)**2,
# the inverse square law of a sound spreading from a point, as loud as its own speaker at 10 cm
SOUND_REF_CM = 10.0


class NxtSoundSensor(LegoSensor):
    KIND = "nxt-sound"
    DRIVER = "lego-nxt-sound"
    MODES = {
        "DB": Mode(1, 1, "pct", "s32", 0, 1000, raw=(0, 5000, 0, 1000)),
        "DBA": Mode(1, 1, "pct", "s32", 0, 1000, raw=(0, 5000, 0, 1000)),
    }
    FACINGS = ("forward", "down")  # it hears all round
    LABEL = "NXT sound"

    def measure(self, mode: str) -> tuple[float, ...]:
        around = self.around
        if not around.others:  # alone in the world: the quiet room or its own speaker
            return (SPEAKER_PCT if around.sound_until_tick > around.tick else QUIET_PCT,)
        x, y, _ = around.sensor_pose(self.mount)
        return (round(around.sound_level(x, y), 1),)
