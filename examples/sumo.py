#!/usr/bin/env python3
"""Sumo: push the other robots out of the ring, and stay in it yourself (mazes/sumo.yaml, sumo-4.yaml).

The robot turns on the spot until its ultrasonic sensor sees something within 70 cm (another
robot: the ring has no walls), then charges at full speed.  When its colour sensor finds the black
line at the ring's edge, it backs into the ring and turns away.  It runs until it is stopped.
Robot: the EV3 driving base (motors on B and C, colour sensor on 3 facing down, ultrasonic on 4).
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

BORDER = 30  # reflected light below this: the black line at the ring's edge
SEES_CM = 70  # something nearer than this ahead is another robot (the ring is 120 cm across)

tank = MoveTank(OUTPUT_B, OUTPUT_C)
floor = ColorSensor(INPUT_3)
eyes = UltrasonicSensor(INPUT_4)

while True:
    if floor.reflected_light_intensity < BORDER:
        tank.on_for_seconds(-50, -50, 0.6)  # back into the ring
        tank.on_for_degrees(50, -50, 200)  # and turn away from the edge
    elif eyes.distance_centimeters < SEES_CM:
        tank.on(100, 100)  # charge
    else:
        tank.on(25, -25)  # look around
