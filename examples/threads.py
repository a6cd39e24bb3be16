#!/usr/bin/env python3
"""Threads: one thread drives while another watches the bumper and blinks the LEDs.

Try it:  ev3sim2d run examples/threads.py
"""

import threading
import time

from ev3dev2.led import Leds
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import TouchSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
bumper = TouchSensor()
leds = Leds()
hit = threading.Event()


def watch_bumper():
    while not bumper.is_pressed:
        time.sleep(0.01)
    hit.set()


def blink():
    on = False
    while not hit.is_set():
        leds.set_color("LEFT", "GREEN" if on else "BLACK")
        on = not on
        time.sleep(0.25)
    leds.set_color("LEFT", "RED")


threading.Thread(target=watch_bumper, daemon=True).start()
threading.Thread(target=blink).start()
tank.on(40, 40)
hit.wait()
tank.off()
print("bumped into the wall after", round(time.monotonic() % 1000, 2), "s")
