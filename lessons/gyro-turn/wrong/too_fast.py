#!/usr/bin/env python3
"""Turns at full speed and stops when the gyro reaches the target: it cannot stop in time.

Loses: turns
"""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_2
from ev3dev2.sensor.lego import GyroSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor(INPUT_2)

for angle in (90, 180, 270):
    target = gyro.angle + angle
    tank.on(SpeedPercent(100), SpeedPercent(-100))
    while gyro.angle < target:
        pass
    tank.off()
    time.sleep(1)
