#!/usr/bin/env python3
"""Never bumps into the robot ahead, because it never moves: it only watches it drive away.

Loses: lap
"""

import time

from ev3dev2.sensor import INPUT_4
from ev3dev2.sensor.lego import UltrasonicSensor

sonar = UltrasonicSensor(INPUT_4)
while True:
    print("robot ahead:", sonar.distance_centimeters, "cm")
    time.sleep(1)
