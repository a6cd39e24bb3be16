#!/usr/bin/env pybricks-micropython
"""Bump and turn (starter, Pybricks): this drives until the touch sensor bumps into the wall.  Now back off, turn, go on."""

from pybricks.ev3devices import ColorSensor, Motor, TouchSensor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
bumper = TouchSensor(Port.S1)
eye = ColorSensor(Port.S3)

robot.drive(150, 0)
while not bumper.pressed():
    wait(10)
robot.stop()
print("bump! the floor here is", eye.color())
