#!/usr/bin/env python3
"""A line follower that stops when the robot ahead is near, but never drives on: the first time the robot
ahead stops, it stops for good and never gets round.

Loses: lap
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)

last_error = 0
while sonar.distance_centimeters > 15:
    error = eye.reflected_light_intensity - 40
    turn = 0.7 * error + 1.5 * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(max(-100, min(100, 35 + turn))), SpeedPercent(max(-100, min(100, 35 - turn))))
tank.off()
