#!/usr/bin/env python3
"""Bump and turn (starter): this drives until the touch sensor bumps into the wall.  Now back off, turn, go on."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_1, INPUT_3
from ev3dev2.sensor.lego import ColorSensor, TouchSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor(INPUT_1)
eye = ColorSensor(INPUT_3)

tank.on(SpeedPercent(30), SpeedPercent(30))
bumper.wait_for_pressed()
tank.off()
print("bump! the floor here is", eye.color_name)
