#!/usr/bin/env pybricks-micropython
"""Motor: the tool motor on port A, moved by angle, to a target, for a time, and read back.

Try it:  ev3sim2d run examples/pybricks/motor.py --maze empty
"""

from pybricks.ev3devices import Motor
from pybricks.parameters import Direction, Port, Stop

arm = Motor(Port.A)  # the medium motor on top of the driving base
print("start", arm.angle())

arm.run_angle(500, 180)  # 500 deg/s, half a turn; then it holds there
print("after run_angle", arm.angle())

arm.run_target(300, 0, then=Stop.HOLD)  # back to where it started
print("after run_target", arm.angle())

arm.run_time(-400, 1000)  # 400 deg/s backwards for one second
print("after run_time", arm.angle())

arm.reset_angle(0)  # call where it is now 0
print("after reset_angle", arm.angle())

wheel = Motor(Port.B, Direction.COUNTERCLOCKWISE)  # the left wheel, counted the other way round
wheel.run_angle(360, 360)  # a full turn of the wheel (backwards, seen from the robot)
print("wheel", wheel.angle())
