#!/usr/bin/env python3
"""Infrared sensor: stop when the wall ahead is close (proximity below 30, about 21 cm).

This one needs a robot with an infrared sensor: examples/robots/ir-base.yaml.
Try it:  ev3sim2d run examples/infrared_sensor.py --robot examples/robots/ir-base.yaml
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import InfraredSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
ir = InfraredSensor()

tank.on(30, 30)
while ir.proximity >= 30:
    pass
tank.off()
print("proximity", ir.proximity)
