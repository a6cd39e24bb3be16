#!/usr/bin/env python3
"""Squares for ever: the program never ends, and at the time limit the robot is anywhere.

Loses: finished
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)


def wheel_degrees(distance_cm):
    return distance_cm / (math.pi * 5.6) * 360


while True:
    tank.on_for_degrees(SpeedPercent(30), SpeedPercent(30), wheel_degrees(50))
    tank.on_for_degrees(SpeedPercent(-20), SpeedPercent(20), wheel_degrees(math.pi * 12 / 4))
