#!/usr/bin/env python3
"""Touch sensor: drive until the bumper hits the wall, back off 10 cm, turn round.

Try it:  ev3sim2d run examples/touch_sensor.py --maze empty
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import TouchSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor()

tank.on(40, 40)
bumper.wait_for_pressed()
tank.off()
print("bump!")
tank.on_for_rotations(-30, -30, 10 / 17.6)  # back off 10 cm
tank.on_for_degrees(30, -30, 360)  # turn round (about 170 degrees)
print("pressed now?", bumper.is_pressed)
