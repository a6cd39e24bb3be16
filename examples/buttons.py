#!/usr/bin/env python3
"""Buttons: wait for Enter, then drive; Down stops the robot.

Presses are scripted in the simulator:
    ev3sim2d run examples/buttons.py --press enter@1.0 --press down@4.0
"""

import time

from ev3dev2.button import Button
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank

buttons = Button()
tank = MoveTank(OUTPUT_B, OUTPUT_C)

print("press Enter to start")
buttons.wait_for_bump("enter")
print("go")
tank.on(30, 30)
while not buttons.down:
    time.sleep(0.01)
tank.off()
print("stopped by Down")
