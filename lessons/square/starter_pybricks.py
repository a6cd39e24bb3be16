#!/usr/bin/env pybricks-micropython
"""Drive a square (starter, Pybricks): this drives the first side and stops.  Add the turns and the other sides."""

from pybricks.ev3devices import Motor
from pybricks.parameters import Port

left = Motor(Port.B)
right = Motor(Port.C)

# One wheel rotation (360 degrees) moves the robot by the wheel's circumference (56 mm wheels).
left.run_angle(300, 720, wait=False)  # 300 deg/s, two rotations; wait=False: start the next motor too
right.run_angle(300, 720)
