#!/usr/bin/env pybricks-micropython
"""Turn with the gyro (starter, Pybricks): one turn to the right, stopped when the gyro says 90.  Make it exact, then add the others."""

from pybricks.ev3devices import GyroSensor, Motor
from pybricks.parameters import Port

left = Motor(Port.B)
right = Motor(Port.C)
gyro = GyroSensor(Port.S2)

start = gyro.angle()  # clockwise is positive
left.run(300)  # deg/s: left wheel forward, right wheel back: a right turn
right.run(-300)
while gyro.angle() < start + 90:
    pass
left.stop()
right.stop()
print("turned", gyro.angle() - start, "degrees")
