#!/usr/bin/env python3
"""A careful line follower at 8% speed: it stays on the line but does not get round in time.

Loses: lap
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

while True:
    turn = 0.3 * (eye.reflected_light_intensity - 40)
    tank.on(SpeedPercent(8 + turn), SpeedPercent(8 - turn))
