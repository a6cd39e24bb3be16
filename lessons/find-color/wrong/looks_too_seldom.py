#!/usr/bin/env python3
"""Fast, and looks at the floor only twice a second: by the time it sees red it is past it.

Loses: on-red
"""

import time

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)

tank.on(SpeedPercent(60), SpeedPercent(60))
while eye.color != ColorSensor.COLOR_RED:
    time.sleep(0.5)
tank.off()
