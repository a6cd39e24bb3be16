#!/usr/bin/env python3
"""Holds its steering over gaps, but steers sharply on the line: at the crossing it turns onto the crossing line.

Loses: straight-over
"""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

lost_at = None
while True:
    light = eye.reflected_light_intensity
    if light > 65:
        if lost_at is None:
            lost_at = time.time()
        steer = 0 if time.time() - lost_at < 1.0 else 15
    else:
        lost_at = None
        steer = 1.2 * (light - 40)
    tank.on(SpeedPercent(max(-100, 25 + steer)), SpeedPercent(max(-100, 25 - steer)))
