#!/usr/bin/env pybricks-micropython
"""Follow the left edge of a dark line with a proportional controller, in LEGO's EV3 MicroPython.

The same robot and the same controller as examples/line_follower.py, written with Pybricks 2.0 the way
LEGO's EV3 MicroPython line follower example is: speeds in mm/s, a turn rate in deg/s (positive turns
right), the reflection as a whole percent, and a 10 ms wait each time round.  Runs as-is on an EV3 with
the EV3 MicroPython image.

Try it:  ev3sim2d run examples/pybricks/line_follower.py --maze line --time 40 --png end.png
"""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

BLACK, WHITE = 5, 75  # reflected light on the tape and on the floor
TARGET = (BLACK + WHITE) / 2  # the edge: half on the line, half off
DRIVE_SPEED = 150  # mm/s
GAIN = 3  # deg/s of turn per point of error

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)

while True:
    error = eye.reflection() - TARGET  # > 0: too much floor, the line is to the right
    robot.drive(DRIVE_SPEED, GAIN * error)
    wait(10)  # as LEGO's example does: drive() and reflection() are quick on a brick, the loop need not spin
