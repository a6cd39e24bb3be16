# ruff: noqa
"""Teleport: find the simulated robot in memory and set it down 10 cm from the wall, without driving.

The program runs inside the simulator's process, so `import ev3sim2d` works and gc holds the
Robot.  It measures the wall with the ultrasonic sensor, as an honest program would, then moves
the robot's physics body forward to 10 cm short of it.  The trace records the robot standing at
the right place: every check passes.

Contained: there is no Robot in the program's process (or nothing that moving it changes): the
robot never moves, and the program scores what standing still scores (never `distance`).
"""

import gc
import math
import time

from ev3dev2.sensor import INPUT_4
from ev3dev2.sensor.lego import UltrasonicSensor

MARKER = "EV3CHEAT-teleport"

sonar = UltrasonicSensor(INPUT_4)
wall_cm = sum(sonar.distance_centimeters for _ in range(5)) / 5
try:
    import ev3sim2d.simulator.robot

    for robot in [o for o in gc.get_objects() if isinstance(o, ev3sim2d.simulator.robot.Robot)]:
        body = robot.body.body
        shift = wall_cm - 10
        heading = robot.heading_rad
        x, y = body.position
        body.position = (x + shift * math.cos(heading), y + shift * math.sin(heading))
        robot.physics.space.reindex_shapes_for_body(body)
except Exception as err:
    print("no robot to move:", err)
time.sleep(0.1)
print("the sensor reads", sonar.distance_centimeters, "cm")
