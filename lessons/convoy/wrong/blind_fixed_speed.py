#!/usr/bin/env python3
"""A line follower at a fixed slow speed, tuned to the pacer shown: it never looks at the robot ahead, so
a robot ahead that stops longer than that one is bumped into.

Loses: no-bump
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

SPEED = 12  # percent: slower than the pacer shown on average, but not than every pacer

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

last_error = 0
while True:
    error = eye.reflected_light_intensity - 40
    turn = 0.35 * error + 0.7 * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(max(-100, min(100, SPEED + turn))), SpeedPercent(max(-100, min(100, SPEED - turn))))
