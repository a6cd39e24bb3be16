#!/usr/bin/env python3
"""Turns by counting wheel rotations for wheels 120 mm apart: wrong on a robot whose wheels sit otherwise.

Loses: turns
"""

import math
import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)


def turn_right(degrees):
    arc_cm = math.pi * 12.0 * degrees / 360
    tank.on_for_degrees(SpeedPercent(20), SpeedPercent(-20), arc_cm / (math.pi * 5.6) * 360)


for angle in (90, 180, 270):
    turn_right(angle)
    time.sleep(1)
