#!/usr/bin/env python3
"""Starts the odometry with its default heading (90 degrees: facing along y), so x is to the right.

Loses: flags
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3EducationSetTire

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)
robot.odometry_start()
for x, y in [(600, 0), (600, 400), (0, 400), (0, 0)]:
    robot.on_to_coordinates(SpeedRPM(40), x, y)
robot.odometry_stop()
