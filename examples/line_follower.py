#!/usr/bin/env python3
"""Follow the left edge of a dark line with a proportional controller (runs as-is on a real EV3).

Try it:  ev3sim2d run examples/line_follower.py --maze line --time 40 --png end.png
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

BLACK, WHITE = 5, 75  # reflected light on the tape and on the floor
TARGET = (BLACK + WHITE) / 2  # the edge: half on the line, half off
BASE_SPEED = 30  # percent
GAIN = 0.6  # percent of speed per point of error

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

while True:
    error = eye.reflected_light_intensity - TARGET  # > 0: too much floor, the line is to the right
    turn = GAIN * error
    left = max(-100, min(100, BASE_SPEED + turn))
    right = max(-100, min(100, BASE_SPEED - turn))
    tank.on(SpeedPercent(left), SpeedPercent(right))
