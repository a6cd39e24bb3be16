#!/usr/bin/env pybricks-micropython
"""Stop on red (starter, Pybricks): drives a little and says what colour the sensor sees.  Make it stop on red."""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

robot.straight(300)
print("I see", eye.color())  # Color.RED on the red patch
