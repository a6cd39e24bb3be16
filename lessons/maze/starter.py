#!/usr/bin/env python3
"""Escape the maze (starter): moves one room ahead if the way is open, and says what it sees.  Make it explore."""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)

print("the wall ahead is", sonar.distance_centimeters, "cm away")
if sonar.distance_centimeters > 25:
    tank.on_for_degrees(SpeedPercent(35), SpeedPercent(35), 40 / (math.pi * 5.6) * 360)  # one room: 40 cm
print("the floor is", eye.color_name)
