#!/usr/bin/env python3
"""Ultrasonic sensor: drive towards the wall ahead and stop 20 cm from it.

Try it:  ev3sim2d run examples/ultrasonic_sensor.py --maze empty
"""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor.lego import UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
sonar = UltrasonicSensor()

print("wall ahead at", sonar.distance_centimeters, "cm")
while sonar.distance_centimeters > 20:
    # slow down as the wall comes near
    speed = min(50, max(10, sonar.distance_centimeters - 15))
    tank.on(speed, speed)
tank.off()
print("stopped at", sonar.distance_centimeters, "cm")
