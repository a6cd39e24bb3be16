#!/usr/bin/env pybricks-micropython
"""Convoy (a solution, Pybricks): follow the line's left edge, and keep your distance from the robot ahead
with the ultrasonic sensor: full speed when it is far, slower as it comes nearer, standing still when it
is close."""

from pybricks.ev3devices import ColorSensor, Motor, UltrasonicSensor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

BLACK, WHITE = 5, 75  # reflected light on the line and on the floor
EDGE = (BLACK + WHITE) / 2  # half on the line, half off
TOP_SPEED = 180  # mm/s, when the road ahead is free
STOP_MM, FREE_MM = 120, 350  # stand still nearer than STOP_MM; slow down between the two
GAIN = 3.4  # deg/s of turning per point of reflected light off the edge
DAMPING = 7  # deg/s per point of change since the last reading


def speed_for(distance_mm):
    """How fast to go with the robot ahead this far away."""
    if distance_mm <= STOP_MM:
        return 0
    if distance_mm >= FREE_MM:
        return TOP_SPEED
    return TOP_SPEED * (distance_mm - STOP_MM) / (FREE_MM - STOP_MM)


robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)
sonar = UltrasonicSensor(Port.S4)

last_error = 0
while True:
    speed = speed_for(sonar.distance())
    if speed == 0:
        robot.drive(0, 0)  # stand still (the drive base holds the wheels where they are)
        continue
    error = eye.reflection() - EDGE  # > 0: too much floor, the line is to the right
    turn = (GAIN * error + DAMPING * (error - last_error)) * speed / TOP_SPEED
    last_error = error
    robot.drive(speed, turn)
