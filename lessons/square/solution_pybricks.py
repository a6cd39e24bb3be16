#!/usr/bin/env pybricks-micropython
"""Drive a square (a solution, Pybricks): a DriveBase that knows the wheel size and spacing drives 500 mm
and turns 90 degrees left, four times."""

from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

SIDE_MM = 500

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)

for _ in range(4):
    robot.straight(SIDE_MM)
    robot.turn(-90)  # in Pybricks 2.0 a positive angle turns right (clockwise): left is negative
