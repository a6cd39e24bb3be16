#!/usr/bin/env python3
"""Visits the three flags but forgets to drive back to the start.

Loses: back-at-start
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3EducationSetTire

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)
robot.odometry_start(theta_degrees_start=0)
for x, y in [(600, 0), (600, 400), (0, 400)]:
    robot.on_to_coordinates(SpeedRPM(40), x, y)
robot.odometry_stop()
