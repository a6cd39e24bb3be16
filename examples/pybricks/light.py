#!/usr/bin/env pybricks-micropython
"""The brick's status light: green while driving, orange while turning, red at the end, then off.

Try it:  ev3sim2d run examples/pybricks/light.py --maze empty
"""

from pybricks.ev3devices import Motor
from pybricks.hubs import EV3Brick
from pybricks.parameters import Color, Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

ev3 = EV3Brick()
robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)

ev3.light.on(Color.GREEN)
robot.straight(200)
ev3.light.on(Color.ORANGE)
robot.turn(90)
ev3.light.on(Color.RED)
wait(500)
ev3.light.off()
print("battery", ev3.battery.voltage(), "mV")
