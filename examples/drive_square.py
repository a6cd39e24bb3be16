#!/usr/bin/env python3
"""Driving: a 40 cm square with MoveTank (straights) and MoveSteering (spins on the spot).

Try it:  ev3sim2d run examples/drive_square.py --maze empty --png square.png
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveSteering, MoveTank, SpeedPercent

WHEEL_CM = 5.6 * 3.14159  # circumference of the EV3 Education tyre
AXLE_CM = 12.0  # distance between the wheels

tank = MoveTank(OUTPUT_B, OUTPUT_C)
steering = MoveSteering(OUTPUT_B, OUTPUT_C)

side_rotations = 40 / WHEEL_CM
# spinning on the spot: each wheel travels a quarter of the circle through both wheels
quarter_turn_rotations = (3.14159 * AXLE_CM / 4) / WHEEL_CM

for side in range(4):
    tank.on_for_rotations(SpeedPercent(40), SpeedPercent(40), side_rotations)
    # steering -100: the wheels turn opposite ways, so the robot turns left on the spot
    steering.on_for_rotations(-100, SpeedPercent(25), quarter_turn_rotations)
    print("side", side + 1, "done")
