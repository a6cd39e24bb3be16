#!/usr/bin/env pybricks-micropython
"""Line with gaps (a solution, Pybricks): a gentle edge follower that holds its recent steering over a gap.

- On the line's edge it steers in proportion to the error, but never sharply: so full black at a
  crossing only nudges it left, and it rolls straight over.
- When the line vanishes (all white) it keeps steering as it did just before: straight on over a
  gap on a straight, still curving in a bend.  If the line stays away for a second, it searches
  to the right, where the line must be.
"""

from pybricks.ev3devices import ColorSensor, Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import StopWatch, wait

EDGE = 40  # reflected light half on the line, half on the floor
WHITE = 65  # above this the sensor sees only floor
SPEED = 128  # mm/s
GAIN = 2  # deg/s of turning per point of error
MOST_TURN = 39  # deg/s: gentle, so a crossing line cannot pull the robot round
SEARCH_TURN = 73  # deg/s to the right, looking for a line lost for good
GAP_MS = 1000  # how long to hold the steering when the line vanishes
LOOP_MS = 15  # one look and one steer each 15 ms: the smoothing below counts in these steps


def clamp(value, limit):
    return max(-limit, min(limit, value))


robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = ColorSensor(Port.S3)
lost = StopWatch()

recent = 0.0  # the turning of the last moments, smoothed
lost_line = False
held = 0.0
while True:
    light = eye.reflection()
    if light > WHITE:
        if not lost_line:
            lost_line = True
            lost.reset()
            held = max(0.0, recent)  # straight on, or on round a right bend
        turn = held if lost.time() < GAP_MS else SEARCH_TURN
    else:
        lost_line = False
        turn = clamp(GAIN * (light - EDGE), MOST_TURN)  # > 0: too much floor, the line is to the right
        recent = 0.9 * recent + 0.1 * turn
    robot.drive(SPEED, turn)
    wait(LOOP_MS)
