#!/usr/bin/env python3
"""Line with gaps (starter): a plain edge follower that gives up where the line ends.  Teach it gaps and crossings."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

while True:
    light = eye.reflected_light_intensity
    if light > 65:
        break  # the line is gone: a gap?
    steer = 0.5 * (light - 40)
    tank.on(SpeedPercent(25 + steer), SpeedPercent(25 - steer))
tank.off()
print("lost the line")
