#!/usr/bin/env python3
"""Stop at the wall (a solution): fast while the wall is far, slow near it, stop at 10 cm."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_4
from ev3dev2.sensor.lego import UltrasonicSensor

STOP_CM = 10
SLOW_CM = 25

tank = MoveTank(OUTPUT_B, OUTPUT_C)
sonar = UltrasonicSensor(INPUT_4)


def distance():
    """The mean of three readings: the sensor is a little noisy."""
    return sum(sonar.distance_centimeters for _ in range(3)) / 3


tank.on(SpeedPercent(40), SpeedPercent(40))
while distance() > SLOW_CM:
    pass
tank.on(SpeedPercent(10), SpeedPercent(10))
while distance() > STOP_CM:
    pass
tank.off()
print("stopped", sonar.distance_centimeters, "cm from the wall")
