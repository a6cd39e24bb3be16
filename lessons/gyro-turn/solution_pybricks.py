#!/usr/bin/env pybricks-micropython
"""Turn with the gyro (a solution, Pybricks): fast until 15 degrees before the target, then slowly; targets
from the start."""

from pybricks.ev3devices import GyroSensor, Motor
from pybricks.parameters import Port
from pybricks.tools import wait

left = Motor(Port.B)
right = Motor(Port.C)
gyro = GyroSensor(Port.S2)
start = gyro.angle()  # clockwise is positive


def spin(speed):
    """Turn on the spot, right for a positive speed (deg/s of each wheel)."""
    left.run(speed)
    right.run(-speed)


def turn_right_to(target):
    """Turn right until the gyro reads `target` degrees from the start."""
    spin(210)
    while gyro.angle() - start < target - 15:
        pass
    spin(40)
    while gyro.angle() - start < target:
        pass
    left.brake()  # stop at once, as tank.off() does; stop() would let it roll
    right.brake()


turn_right_to(90)
wait(1000)
turn_right_to(90 + 180)
wait(1000)
turn_right_to(90 + 180 + 270)
print("turned", gyro.angle() - start, "degrees in all")
