#!/usr/bin/env pybricks-micropython
"""Drive to coordinates (starter, Pybricks): the way to the first flag.  Add the others and the way back."""

from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(
    Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120
)  # 120 mm between the wheels
robot.straight(600)  # x (mm) is straight ahead, y to the left
print("at", robot.distance(), "mm, turned", robot.angle(), "degrees")
