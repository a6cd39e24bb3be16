#!/usr/bin/env python3
"""Stop on red (starter): drives a little and says what colour the sensor sees.  Make it stop on red."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

tank.on_for_seconds(SpeedPercent(30), SpeedPercent(30), 2)
print("I see", eye.color_name)  # 'Red' on the red patch
