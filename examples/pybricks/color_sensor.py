#!/usr/bin/env pybricks-micropython
"""Colour sensor: drive across the colour patches of the `colors` world, say each colour, stop on red.

Try it:  ev3sim2d run examples/pybricks/color_sensor.py --maze colors
"""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Color, Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)  # looking down at the floor

print("reflection", eye.reflection(), "ambient", eye.ambient(), "rgb", eye.rgb())
robot.drive(100, 0)
seen = None
while seen != Color.RED:
    color = eye.color()  # a Color, or None where it sees no colour
    if color != seen and color is not None:
        print(color)
    seen = color
robot.stop(Stop.BRAKE)
