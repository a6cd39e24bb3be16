#!/usr/bin/env python3
"""Drive to coordinates (a solution): odometry from the start, facing along x; each flag, then home."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveDifferential, SpeedRPM
from ev3dev2.wheel import EV3EducationSetTire

FLAGS_MM = [(600, 0), (600, 400), (0, 400)]

robot = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)  # 120 mm between the wheels
robot.odometry_start(theta_degrees_start=0)  # x straight ahead, y to the left, in mm
for x, y in FLAGS_MM + [(0, 0)]:
    robot.on_to_coordinates(SpeedRPM(40), x, y)
    print("at", round(robot.x_pos_mm), round(robot.y_pos_mm))
robot.odometry_stop()
