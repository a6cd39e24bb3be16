#!/usr/bin/env python3
"""LEDs: the two brick lights in every colour, then amber while the robot drives.

Try it:  ev3sim2d run examples/leds.py
"""

import time

from ev3dev2.led import Leds
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank

leds = Leds()
for colour in ("RED", "GREEN", "AMBER", "ORANGE", "YELLOW", "BLACK"):
    leds.set_color("LEFT", colour)
    leds.set_color("RIGHT", colour)
    time.sleep(0.3)

leds.set_color("LEFT", "AMBER")
MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)
leds.all_off()
