#!/usr/bin/env pybricks-micropython
"""Bump and turn (a solution, Pybricks): forward until a bump or green; on a bump back off 5 cm and turn right."""

from pybricks.ev3devices import ColorSensor, Motor, TouchSensor
from pybricks.parameters import Color, Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
bumper = TouchSensor(Port.S1)
eye = ColorSensor(Port.S3)

while True:
    robot.drive(150, 0)
    while not bumper.pressed() and eye.color() != Color.GREEN:
        pass
    robot.stop(Stop.BRAKE)  # at once, not rolling on into the wall
    if eye.color() == Color.GREEN:
        break
    robot.straight(-50)  # back off 5 cm
    robot.turn(90)  # a positive angle turns right (clockwise)
print("green!")
