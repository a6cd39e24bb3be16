#!/usr/bin/env python3
"""Drive a square (a solution): 50 cm sides and left turns worked out from the wheel size and spacing."""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

WHEEL_DIAMETER_CM = 5.6
AXLE_TRACK_CM = 12.0  # distance between the middles of the two wheels
SIDE_CM = 50

tank = MoveTank(OUTPUT_B, OUTPUT_C)


def wheel_degrees(distance_cm):
    """How far a wheel turns (degrees) to roll distance_cm."""
    return distance_cm / (math.pi * WHEEL_DIAMETER_CM) * 360


def forward(distance_cm):
    tank.on_for_degrees(SpeedPercent(30), SpeedPercent(30), wheel_degrees(distance_cm))


def turn_left(degrees):
    # turning on the spot, each wheel rolls along a circle whose diameter is the axle track
    arc_cm = math.pi * AXLE_TRACK_CM * degrees / 360
    tank.on_for_degrees(SpeedPercent(-20), SpeedPercent(20), wheel_degrees(arc_cm))


for _ in range(4):
    forward(SIDE_CM)
    turn_left(90)
