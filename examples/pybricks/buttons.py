#!/usr/bin/env pybricks-micropython
"""The brick's buttons: wait for the centre button, then drive; the down button stops the robot.

Presses are scripted in the simulator:
    ev3sim2d run examples/pybricks/buttons.py --press enter@1.0 --press down@4.0
"""

from pybricks.ev3devices import Motor
from pybricks.hubs import EV3Brick
from pybricks.parameters import Button, Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

ev3 = EV3Brick()
robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)

print("press the centre button to start")
while Button.CENTER not in ev3.buttons.pressed():  # pressed() is a list of the buttons held now
    wait(10)
print("go")
robot.drive(150, 0)
while Button.DOWN not in ev3.buttons.pressed():
    wait(10)
robot.stop()
print("stopped by", Button.DOWN)
