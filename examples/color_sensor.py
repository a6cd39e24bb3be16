#!/usr/bin/env python3
"""Colour sensor: drive across the colour patches and say each colour, then stop on red.

Try it:  ev3sim2d run examples/color_sensor.py --maze colors
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor()

last = None
tank.on(20, 20)
while True:
    name = eye.color_name
    if name != last:
        print(name, "reflected", eye.reflected_light_intensity, "rgb", eye.rgb)
        last = name
    if name == "Red":
        tank.off()
        break
