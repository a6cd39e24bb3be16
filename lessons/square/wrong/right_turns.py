#!/usr/bin/env python3
"""A square driven the wrong way round: it turns right at each corner.

Loses: corners
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)


def wheel_degrees(distance_cm):
    return distance_cm / (math.pi * 5.6) * 360


for _ in range(4):
    tank.on_for_degrees(SpeedPercent(30), SpeedPercent(30), wheel_degrees(50))
    tank.on_for_degrees(SpeedPercent(20), SpeedPercent(-20), wheel_degrees(math.pi * 12 / 4))
