#!/usr/bin/env python3
"""Counts wheel turns for the distance in the room it was tried in: wrong wherever the wall is elsewhere.

Loses: distance
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_degrees(SpeedPercent(40), SpeedPercent(40), 152 / (math.pi * 5.6) * 360)
