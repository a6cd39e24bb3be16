#!/usr/bin/env pybricks-micropython
"""Follow the line (starter, Pybricks): this shows what the colour sensor sees while driving straight.  Make it steer."""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

robot.drive(100, 0)  # 100 mm/s straight ahead
for _ in range(10):
    print("reflected light:", eye.reflection())  # about 5 on the line, 75 on the floor
    wait(200)
robot.stop()
