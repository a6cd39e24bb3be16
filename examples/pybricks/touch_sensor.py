#!/usr/bin/env pybricks-micropython
"""Touch sensor: drive until the bumper hits the wall, back off 10 cm, turn round.

Try it:  ev3sim2d run examples/pybricks/touch_sensor.py --maze empty
"""

from pybricks.ev3devices import Motor, TouchSensor
from pybricks.parameters import Port, Stop
from pybricks.robotics import DriveBase
from pybricks.tools import wait

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
bumper = TouchSensor(Port.S1)

robot.drive(200, 0)  # 200 mm/s straight ahead
while not bumper.pressed():
    wait(10)
robot.stop(Stop.BRAKE)
print("bump!")
robot.straight(-100)  # back off 10 cm
robot.turn(180)  # turn round
print("pressed now?", bumper.pressed())
