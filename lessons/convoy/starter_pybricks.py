#!/usr/bin/env pybricks-micropython
"""Convoy (starter, Pybricks): this drives a little way and shows what the ultrasonic sensor sees of the robot ahead.
Make it follow the line, and slow down or stop when the robot ahead is near."""

from pybricks.ev3devices import ColorSensor, Motor, UltrasonicSensor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)
sonar = UltrasonicSensor(Port.S4)

robot.drive(50, 0)
for _ in range(10):
    print("robot ahead:", sonar.distance(), "mm; reflected light:", eye.reflection())
    wait(200)
robot.stop()
