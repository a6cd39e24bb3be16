#!/usr/bin/env python3
"""Turns as soon as it bumps, without backing off: its front corners scrape along the wall.

Loses: no-scrape
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_1, INPUT_3
from ev3dev2.sensor.lego import ColorSensor, TouchSensor

WHEEL_CM = math.pi * 5.6
tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor(INPUT_1)
eye = ColorSensor(INPUT_3)

while eye.color != ColorSensor.COLOR_GREEN:
    tank.on(SpeedPercent(30), SpeedPercent(30))
    while not bumper.is_pressed and eye.color != ColorSensor.COLOR_GREEN:
        pass
    tank.off()
    if bumper.is_pressed:
        tank.on_for_rotations(SpeedPercent(20), SpeedPercent(-20), math.pi * 12 / 4 / WHEEL_CM)
