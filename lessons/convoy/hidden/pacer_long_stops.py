#!/usr/bin/env python3
"""The robot ahead in the convoy lesson (the lesson's own program, not the student's): follows the line's
left edge slowly, and stops often and long: 4 s after every 4 s of driving."""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

EDGE = 40  # reflected light half on the line, half off
SPEED = 20  # percent
DRIVE_S, STOP_S = 4.0, 4.0  # drive this long, then stand this long, again and again

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)  # so that it never runs into a robot it comes round to from behind

start = time.monotonic()
last_error = 0
while True:
    if (time.monotonic() - start) % (DRIVE_S + STOP_S) >= DRIVE_S or sonar.distance_centimeters < 12:
        tank.off(brake=True)
        time.sleep(0.05)
        continue
    error = eye.reflected_light_intensity - EDGE
    turn = 0.5 * error + 1.0 * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(max(-100, min(100, SPEED + turn))), SpeedPercent(max(-100, min(100, SPEED - turn))))
