#!/usr/bin/env python3
"""Drives until the touch sensor bumps into the wall: it touches the wall and stops far too close.

Loses: distance
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_1
from ev3dev2.sensor.lego import TouchSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor(INPUT_1)

tank.on(SpeedPercent(40), SpeedPercent(40))
bumper.wait_for_pressed()
tank.off()
