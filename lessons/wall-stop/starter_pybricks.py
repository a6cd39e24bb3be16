#!/usr/bin/env pybricks-micropython
"""Stop at the wall (starter, Pybricks): this reads the ultrasonic sensor once and drives a little.  Make it stop at 10 cm."""

from pybricks.ev3devices import Motor, UltrasonicSensor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
sonar = UltrasonicSensor(Port.S4)

print("the wall is", sonar.distance(), "mm away")
robot.straight(150)
