#!/usr/bin/env python3
"""Bump and turn (a solution): forward until a bump or green; on a bump back off 5 cm and turn right."""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_1, INPUT_3
from ev3dev2.sensor.lego import ColorSensor, TouchSensor

WHEEL_CM = math.pi * 5.6  # how far one wheel rotation rolls
AXLE_TRACK_CM = 12.0

tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor(INPUT_1)
eye = ColorSensor(INPUT_3)


def on_green():
    return eye.color == ColorSensor.COLOR_GREEN


while True:
    tank.on(SpeedPercent(30), SpeedPercent(30))
    while not bumper.is_pressed and not on_green():
        pass
    tank.off()
    if on_green():
        break
    tank.on_for_rotations(SpeedPercent(-20), SpeedPercent(-20), 5 / WHEEL_CM)  # back off 5 cm
    quarter_turn_cm = math.pi * AXLE_TRACK_CM / 4
    tank.on_for_rotations(SpeedPercent(20), SpeedPercent(-20), quarter_turn_cm / WHEEL_CM)  # turn right
print("green!")
