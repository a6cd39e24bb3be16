#!/usr/bin/env python3
"""Turn with the gyro (a solution): fast until 15 degrees before the target, then slowly; targets from the start."""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_2
from ev3dev2.sensor.lego import GyroSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor(INPUT_2)
start = gyro.angle  # clockwise is positive


def turn_right_to(target):
    """Turn right until the gyro reads `target` degrees from the start."""
    tank.on(SpeedPercent(20), SpeedPercent(-20))
    while gyro.angle - start < target - 15:
        pass
    tank.on(SpeedPercent(4), SpeedPercent(-4))
    while gyro.angle - start < target:
        pass
    tank.off()


turn_right_to(90)
time.sleep(1)
turn_right_to(90 + 180)
time.sleep(1)
turn_right_to(90 + 180 + 270)
print("turned", gyro.angle - start, "degrees in all")
