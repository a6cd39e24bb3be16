#!/usr/bin/env pybricks-micropython
"""Stop on red (a solution, Pybricks): drive, read the colour as often as possible, stop at the first red."""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Color, Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

robot.drive(150, 0)
while eye.color() != Color.RED:
    pass
robot.stop(Stop.BRAKE)
print("red!")
