#!/usr/bin/env pybricks-micropython
"""Stop at the wall (a solution, Pybricks): fast while the wall is far, slow near it, stop at 10 cm."""

from pybricks.ev3devices import Motor, UltrasonicSensor
from pybricks.parameters import Port, Stop
from pybricks.robotics import DriveBase

STOP_MM = 100
SLOW_MM = 250

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
sonar = UltrasonicSensor(Port.S4)


def distance():
    """The mean of three readings (mm): the sensor is a little noisy."""
    return sum(sonar.distance() for _ in range(3)) / 3


robot.drive(200, 0)  # mm/s, no turning
while distance() > SLOW_MM:
    pass
robot.drive(50, 0)
while distance() > STOP_MM:
    pass
robot.stop(Stop.BRAKE)
print("stopped", sonar.distance(), "mm from the wall")
