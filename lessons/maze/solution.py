#!/usr/bin/env python3
"""Escape the maze (a solution): keep a wall on the right, room by room, until the floor is green.

In each room: look right, ahead, left (turning with the gyro, measuring with the ultrasonic
sensor) and take the first way that is open; if none is, turn back.  A maze without loops is
always solved this way.
"""

import math

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_2, INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, GyroSensor, UltrasonicSensor

ROOM_CM = 40  # from the middle of one room to the middle of the next
OPEN_CM = 25  # farther than this, the way ahead is open (a wall in a room is 7 cm from the sensor)

tank = MoveTank(OUTPUT_B, OUTPUT_C)
gyro = GyroSensor(INPUT_2)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)

heading = gyro.angle  # where the robot should face, in gyro degrees (clockwise)


def turn_to(target):
    """Turn on the spot until the gyro reads target: fast, then slowly for the last degrees."""
    right = target > gyro.angle
    sign = 1 if right else -1
    tank.on(SpeedPercent(20 * sign), SpeedPercent(-20 * sign))
    while (target - gyro.angle) * sign > 12:
        pass
    tank.on(SpeedPercent(4 * sign), SpeedPercent(-4 * sign))
    while (target - gyro.angle) * sign > 0:
        pass
    tank.off()


def turn(degrees):
    """Turn by degrees (clockwise positive) from where the robot should face."""
    global heading
    heading += degrees
    turn_to(heading)


def open_ahead():
    return sonar.distance_centimeters > OPEN_CM


def forward_one_room():
    tank.on_for_degrees(SpeedPercent(35), SpeedPercent(35), ROOM_CM / (math.pi * 5.6) * 360)


while eye.color != ColorSensor.COLOR_GREEN:
    turn(90)  # look right
    if not open_ahead():
        turn(-90)  # look ahead
        if not open_ahead():
            turn(-90)  # look left
            if not open_ahead():
                turn(-90)  # a dead end: back the way we came
    forward_one_room()
print("found the goal")
