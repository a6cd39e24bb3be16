#!/usr/bin/env python3
"""Odometry: MoveDifferential drives a 50 cm square by coordinates and knows where it is.

Try it:  ev3sim2d run examples/odometry.py --maze empty --png odometry.png
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3EducationSetTire

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)  # 120 mm between the wheels

# the odometry thread tracks x, y (mm) and the heading, starting at (0, 0) facing along +x
robot.odometry_start(theta_degrees_start=0)
for x, y in ((500, 0), (500, 500), (0, 500), (0, 0)):
    robot.on_to_coordinates(SpeedRPM(40), x, y)
    print("at", round(robot.x_pos_mm), round(robot.y_pos_mm))
robot.turn_to_angle(SpeedRPM(40), 0)
robot.odometry_stop()
