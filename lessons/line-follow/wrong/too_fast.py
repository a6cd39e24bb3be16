#!/usr/bin/env python3
"""A line follower at 80% speed with a gentle steer: it overshoots the first bend and loses the line.

Loses: on-line
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

while True:
    turn = 0.4 * (eye.reflected_light_intensity - 40)
    tank.on(SpeedPercent(max(-100, min(100, 80 + turn))), SpeedPercent(max(-100, min(100, 80 - turn))))
