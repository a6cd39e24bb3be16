#!/usr/bin/env python3
"""Display: draw on the brick's 178 x 128 LCD (the video shows it in the side panel).

Try it:  ev3sim2d run examples/display.py
"""

import time

from ev3dev2.display import Display
from ev3dev2.sensor.lego import UltrasonicSensor

lcd = Display()
sonar = UltrasonicSensor()

for _ in range(3):
    lcd.clear()
    lcd.draw.rectangle((0, 0, 177, 127), outline="black")
    lcd.draw.text((10, 10), "Hello, EV3!")
    lcd.draw.text((10, 40), f"wall at {sonar.distance_centimeters:.0f} cm")
    lcd.draw.ellipse((120, 60, 160, 100), fill="black")
    lcd.update()
    time.sleep(1)
