#!/usr/bin/env pybricks-micropython
"""Gyro sensor: turn left on the spot until the gyro has turned 90 degrees, then say how far it went.

Try it:  ev3sim2d run examples/pybricks/gyro_sensor.py --maze empty
"""

from pybricks.ev3devices import GyroSensor, Motor
from pybricks.parameters import Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
gyro = GyroSensor(Port.S2)
gyro.reset_angle(0)

robot.drive(0, -60)  # turn left (counter-clockwise) at 60 deg/s
while gyro.angle() > -90:  # the gyro counts clockwise as positive
    pass
robot.stop(Stop.BRAKE)
print("turned", -gyro.angle(), "degrees left, now at", gyro.speed(), "deg/s")
