#!/usr/bin/env python3
"""Drive a square (starter): this drives the first side and stops.  Add the turns and the other sides."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

tank = MoveTank(OUTPUT_B, OUTPUT_C)

# One wheel rotation moves the robot by the wheel's circumference (56 mm wheels).
tank.on_for_rotations(SpeedPercent(30), SpeedPercent(30), 2)
