#!/usr/bin/env python3
"""Convoy (starter): this drives a little way and shows what the ultrasonic sensor sees of the robot ahead.
Make it follow the line, and slow down or stop when the robot ahead is near."""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)

tank.on(SpeedPercent(10), SpeedPercent(10))
for _ in range(10):
    print("robot ahead:", sonar.distance_centimeters, "cm; reflected light:", eye.reflected_light_intensity)
    time.sleep(0.2)
tank.off()
