#!/usr/bin/env python3
"""Tells MoveDifferential the robot has the small EV3Tire (43.2 mm), not the 56 mm education set tyre: every distance comes out long.

Loses: flags
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3Tire

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3Tire, 120)
robot.odometry_start(theta_degrees_start=0)
for x, y in [(600, 0), (600, 400), (0, 400), (0, 0)]:
    robot.on_to_coordinates(SpeedRPM(40), x, y)
robot.odometry_stop()
