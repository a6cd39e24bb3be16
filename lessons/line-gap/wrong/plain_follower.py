#!/usr/bin/env python3
"""A plain proportional edge follower: at a gap it sees only floor and turns round looking for the line.

Loses: on-line
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

while True:
    steer = 0.6 * (eye.reflected_light_intensity - 40)
    tank.on(SpeedPercent(30 + steer), SpeedPercent(30 - steer))
