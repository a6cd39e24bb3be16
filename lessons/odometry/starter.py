#!/usr/bin/env python3
"""Drive to coordinates (starter): odometry on, and the way to the first flag.  Add the others and the way back."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3EducationSetTire

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)  # 120 mm between the wheels
robot.odometry_start(theta_degrees_start=0)  # x (mm) straight ahead, y to the left
robot.on_to_coordinates(SpeedRPM(40), 600, 0)
print("at", round(robot.x_pos_mm), round(robot.y_pos_mm))
robot.odometry_stop()
