#!/usr/bin/env python3
"""Gyro sensor: turn exactly 90 degrees to the right, watching the gyro (clockwise is positive).

Try it:  ev3sim2d run examples/gyro_sensor.py
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import GyroSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor()
gyro.reset()

tank.on(15, -15)  # left wheel forward, right wheel back: a right turn
while gyro.angle < 90:
    pass
tank.off()
print("turned", gyro.angle, "degrees; rate now", gyro.rate)
