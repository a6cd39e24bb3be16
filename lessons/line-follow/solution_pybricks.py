#!/usr/bin/env pybricks-micropython
"""Follow the line (a solution, Pybricks): steer along the line's left edge, in proportion to how far off it
the sensor is."""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

BLACK, WHITE = 5, 75  # reflected light on the line and on the floor
EDGE = (BLACK + WHITE) / 2  # half on the line, half off
SPEED = 180  # mm/s
GAIN = 3.4  # deg/s of turning per point of reflected light off the edge
DAMPING = 7  # deg/s per point of change since the last reading
LOOP_MS = 15  # one look and one steer each 15 ms: the damping counts the change over this time

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

last_error = 0
while True:
    error = eye.reflection() - EDGE  # > 0: too much floor, the line is to the right
    robot.drive(SPEED, GAIN * error + DAMPING * (error - last_error))  # a positive turn rate turns right
    last_error = error
    wait(LOOP_MS)
