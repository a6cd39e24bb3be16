#!/usr/bin/env pybricks-micropython
"""Infrared sensor: drive at the wall until the proximity reads 25 % or less, then say how near it is.

The driving base with an infrared sensor in place of the ultrasonic one (examples/robots/ir-base.yaml).

Try it:  ev3sim2d run examples/pybricks/infrared_sensor.py --maze empty --robot examples/robots/ir-base.yaml
"""

from pybricks.ev3devices import InfraredSensor, Motor
from pybricks.parameters import Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
eye = InfraredSensor(Port.S4)

robot.drive(150, 0)
while eye.distance() > 25:  # a relative distance: 0 (touching) to 100 (far)
    pass
robot.stop(Stop.BRAKE)
print("proximity", eye.distance())
