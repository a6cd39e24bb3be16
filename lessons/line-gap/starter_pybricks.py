#!/usr/bin/env pybricks-micropython
"""Line with gaps (starter, Pybricks): a plain edge follower that gives up where the line ends.  Teach it gaps and crossings."""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

while True:
    light = eye.reflection()
    if light > 65:
        break  # the line is gone: a gap?
    robot.drive(130, 2.5 * (light - 40))  # mm/s, and deg/s of turning (positive: right)
robot.stop()
print("lost the line")
