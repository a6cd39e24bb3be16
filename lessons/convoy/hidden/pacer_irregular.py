#!/usr/bin/env python3
"""The robot ahead in a hidden variant of the convoy lesson: follows the line's left edge a little faster
than the visible pacer, and stops at irregular times for irregular lengths, the first time soon."""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

EDGE = 40  # reflected light half on the line, half off
SPEED = 25  # percent
STOPS = [(2, 3), (9, 1), (14, 6), (27, 2), (31, 5), (45, 1), (52, 4), (66, 3), (80, 2)]  # (at s, for s)

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)  # so that it never runs into a robot it comes round to from behind


def stopped_now(t):
    return any(at <= t < at + length for at, length in STOPS)


start = time.monotonic()
last_error = 0
while True:
    if stopped_now(time.monotonic() - start) or sonar.distance_centimeters < 12:
        tank.off(brake=True)
        time.sleep(0.05)
        continue
    error = eye.reflected_light_intensity - EDGE
    turn = 0.6 * error + 1.2 * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(max(-100, min(100, SPEED + turn))), SpeedPercent(max(-100, min(100, SPEED - turn))))
