#!/usr/bin/env python3
"""Stops on the first patch that is not white floor, whatever its colour.

Loses: on-red
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

tank.on(SpeedPercent(30), SpeedPercent(30))
while eye.color == ColorSensor.COLOR_WHITE:
    pass
tank.off()
