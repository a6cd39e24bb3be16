#!/usr/bin/env pybricks-micropython
"""Drive to coordinates (a solution, Pybricks): keep track of where the robot is, from the start, facing
along x; turn towards each flag and drive straight to it, then home."""

import math

from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

FLAGS_MM = [(600, 0), (600, 400), (0, 400)]

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
x, y, heading = 0.0, 0.0, 0.0  # mm, mm, degrees counter-clockwise from x (y is to the left)


def go_to(to_x, to_y):
    """Turn towards (to_x, to_y), drive there, and remember where the robot is."""
    global x, y, heading
    bearing = math.degrees(math.atan2(to_y - y, to_x - x))
    turn = (bearing - heading + 180) % 360 - 180  # the shorter way round
    robot.turn(-turn)  # Pybricks turns clockwise for a positive angle; ours is counter-clockwise
    robot.straight(math.hypot(to_x - x, to_y - y))
    x, y, heading = to_x, to_y, bearing


for flag in FLAGS_MM + [(0, 0)]:
    go_to(*flag)
    print("at", round(x), round(y))
