#!/usr/bin/env python3
"""Turns the whole 540 degrees in one go, without the pauses between the turns.

Loses: turns
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_2
from ev3dev2.sensor.lego import GyroSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor(INPUT_2)

start = gyro.angle
tank.on(SpeedPercent(20), SpeedPercent(-20))
while gyro.angle - start < 540 - 15:
    pass
tank.on(SpeedPercent(4), SpeedPercent(-4))
while gyro.angle - start < 540:
    pass
tank.off()
