#!/usr/bin/env python3
"""Follow the line (starter): this shows what the colour sensor sees while driving straight.  Make it steer."""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

tank.on(SpeedPercent(20), SpeedPercent(20))
for _ in range(10):
    print("reflected light:", eye.reflected_light_intensity)  # about 5 on the line, 75 on the floor
    time.sleep(0.2)
tank.off()
