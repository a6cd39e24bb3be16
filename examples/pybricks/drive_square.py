#!/usr/bin/env pybricks-micropython
"""Drive base: a square of 40 cm sides with DriveBase.straight and DriveBase.turn, then home by drive().

A DriveBase knows the wheels (56 mm across) and their spacing (120 mm apart), so it drives in mm and
turns in degrees; in Pybricks 2.0 a positive angle turns right (clockwise).

Try it:  ev3sim2d run examples/pybricks/drive_square.py --maze empty
"""

from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)

for side in range(1, 5):
    robot.straight(400)  # mm; waits until the robot is there
    robot.turn(-90)  # a quarter turn to the left
    print("side", side, "done")
print("driven", robot.distance(), "mm, turned", robot.angle(), "degrees")
