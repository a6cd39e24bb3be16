#!/usr/bin/env pybricks-micropython
"""Ultrasonic sensor: drive at the wall and stop 20 cm from it.

Try it:  ev3sim2d run examples/pybricks/ultrasonic_sensor.py --maze empty
"""

from pybricks.ev3devices import Motor, UltrasonicSensor
from pybricks.parameters import Port, Stop
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
sonar = UltrasonicSensor(Port.S4)

print("presence of another sensor?", sonar.presence())
robot.drive(200, 0)
while sonar.distance() > 300:  # mm
    pass
robot.drive(50, 0)  # slowly for the last 10 cm
while sonar.distance() > 200:
    pass
robot.stop(Stop.BRAKE)
print("wall at", sonar.distance(), "mm")
