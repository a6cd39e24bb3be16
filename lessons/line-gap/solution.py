#!/usr/bin/env python3
"""Line with gaps (a solution): a gentle edge follower that holds its recent steering over a gap.

- On the line's edge it steers in proportion to the error, but never sharply: so full black at a
  crossing only nudges it left, and it rolls straight over.
- When the line vanishes (all white) it keeps steering as it did just before: straight on over a
  gap on a straight, still curving in a bend.  If the line stays away for a second, it searches
  to the right, where the line must be.
"""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

EDGE = 40  # reflected light half on the line, half on the floor
WHITE = 65  # above this the sensor sees only floor
SPEED = 25  # percent
GAIN = 0.4  # percent of steering per point of error
MOST_STEER = 8  # percent: gentle, so a crossing line cannot pull the robot round
GAP_S = 1.0  # how long to hold the steering when the line vanishes


def clamp(value, limit):
    return max(-limit, min(limit, value))


tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

recent = 0.0  # the steering of the last moments, smoothed
lost_at = None
held = 0.0
while True:
    light = eye.reflected_light_intensity
    if light > WHITE:
        if lost_at is None:
            lost_at = time.time()
            held = max(0.0, recent)  # straight on, or on round a right bend
        steer = held if time.time() - lost_at < GAP_S else 15
    else:
        lost_at = None
        steer = clamp(GAIN * (light - EDGE), MOST_STEER)  # > 0: too much floor, the line is to the right
        recent = 0.9 * recent + 0.1 * steer
    tank.on(SpeedPercent(SPEED + steer), SpeedPercent(SPEED - steer))
