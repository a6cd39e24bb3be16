#!/usr/bin/env python3
"""Stop at the wall (starter): this reads the ultrasonic sensor once and drives a little.  Make it stop at 10 cm."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_4
from ev3dev2.sensor.lego import UltrasonicSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
sonar = UltrasonicSensor(INPUT_4)

print("the wall is", sonar.distance_centimeters, "cm away")
tank.on_for_seconds(SpeedPercent(30), SpeedPercent(30), 1)
