#!/usr/bin/env python3
"""A good line follower that never looks at the robot ahead: it catches up and bumps into it.

Loses: no-bump
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

last_error = 0
while True:
    error = eye.reflected_light_intensity - 40
    turn = 0.7 * error + 1.5 * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(max(-100, min(100, 35 + turn))), SpeedPercent(max(-100, min(100, 35 - turn))))
