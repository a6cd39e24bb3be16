#!/usr/bin/env python3
"""Follow the line (a solution): steer along the line's left edge, in proportion to how far off it the sensor is."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

BLACK, WHITE = 5, 75  # reflected light on the line and on the floor
EDGE = (BLACK + WHITE) / 2  # half on the line, half off
SPEED = 35  # percent
GAIN = 0.7  # percent of speed per point of reflected light off the edge
DAMPING = 1.5  # percent per point of change since the last reading


def clamp(value):
    return max(-100, min(100, value))


tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

last_error = 0
while True:
    error = eye.reflected_light_intensity - EDGE  # > 0: too much floor, the line is to the right
    turn = GAIN * error + DAMPING * (error - last_error)
    last_error = error
    tank.on(SpeedPercent(clamp(SPEED + turn)), SpeedPercent(clamp(SPEED - turn)))
