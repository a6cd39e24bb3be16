#!/usr/bin/env python3
"""Turn with the gyro (starter): one turn to the right, stopped when the gyro says 90.  Make it exact, then add the others."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_2
from ev3dev2.sensor.lego import GyroSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor(INPUT_2)

start = gyro.angle  # clockwise is positive
tank.on(SpeedPercent(30), SpeedPercent(-30))  # left wheel forward, right wheel back: a right turn
while gyro.angle < start + 90:
    pass
tank.off()
print("turned", gyro.angle - start, "degrees")
