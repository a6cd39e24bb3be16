#!/usr/bin/env python3
"""A square whose turns are timed by guess, not worked out: each turn is about 80 degrees.

Loses: back-at-start, facing-ahead
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)

for _ in range(4):
    tank.on_for_rotations(SpeedPercent(30), SpeedPercent(30), 2.84)
    tank.on_for_seconds(SpeedPercent(-20), SpeedPercent(20), 0.82)
