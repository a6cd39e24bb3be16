#!/usr/bin/env pybricks-micropython
"""Escape the maze (a solution, Pybricks): keep a wall on the right, room by room, until the floor is green.

In each room: look right, ahead, left (turning with the gyro, measuring with the ultrasonic
sensor) and take the first way that is open; if none is, turn back.  A maze without loops is
always solved this way.
"""

from pybricks.ev3devices import ColorSensor, GyroSensor, Motor, UltrasonicSensor
from pybricks.parameters import Color, Port, Stop
from pybricks.robotics import DriveBase

ROOM_MM = 400  # from the middle of one room to the middle of the next
OPEN_MM = 250  # farther than this, the way ahead is open (a wall in a room is 70 mm from the sensor)

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
gyro = GyroSensor(Port.S2)
eye = ColorSensor(Port.S3)
sonar = UltrasonicSensor(Port.S4)

heading = gyro.angle()  # where the robot should face, in gyro degrees (clockwise)


def turn_to(target):
    """Turn on the spot until the gyro reads target: fast, then slowly for the last degrees."""
    sign = 1 if target > gyro.angle() else -1  # 1: turn right (clockwise)
    robot.drive(0, 100 * sign)
    while (target - gyro.angle()) * sign > 12:
        pass
    robot.drive(0, 20 * sign)
    while (target - gyro.angle()) * sign > 0:
        pass
    robot.stop(Stop.BRAKE)


def turn(degrees):
    """Turn by degrees (clockwise positive) from where the robot should face."""
    global heading
    heading += degrees
    turn_to(heading)


def open_ahead():
    return sonar.distance() > OPEN_MM


while eye.color() != Color.GREEN:
    turn(90)  # look right
    if not open_ahead():
        turn(-90)  # look ahead
        if not open_ahead():
            turn(-90)  # look left
            if not open_ahead():
                turn(-90)  # a dead end: back the way we came
    robot.straight(ROOM_MM)
print("found the goal")
