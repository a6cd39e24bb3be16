#!/usr/bin/env python3
"""Sees the wall at 10 cm and ends, but never stops the motors: a real robot drives on into the wall.

Loses: stopped
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_4
from ev3dev2.sensor.lego import UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
sonar = UltrasonicSensor(INPUT_4)

tank.on(SpeedPercent(20), SpeedPercent(20))
while sonar.distance_centimeters > 10:
    pass
print("the wall!")
