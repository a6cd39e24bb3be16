#!/usr/bin/env pybricks-micropython
"""Escape the maze (starter, Pybricks): moves one room ahead if the way is open, and says what it sees.  Make it explore."""

from pybricks.ev3devices import ColorSensor, Motor, UltrasonicSensor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)
sonar = UltrasonicSensor(Port.S4)

print("the wall ahead is", sonar.distance(), "mm away")
if sonar.distance() > 250:
    robot.straight(400)  # one room: 40 cm
print("the floor is", eye.color())
