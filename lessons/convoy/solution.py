#!/usr/bin/env python3
"""Convoy (a solution): follow the line's left edge, and keep your distance from the robot ahead with the
ultrasonic sensor: full speed when it is far, slower as it comes nearer, standing still when it is close."""

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor

BLACK, WHITE = 5, 75  # reflected light on the line and on the floor
EDGE = (BLACK + WHITE) / 2  # half on the line, half off
TOP_SPEED = 35  # percent, when the road ahead is free
STOP_CM, FREE_CM = 12, 35  # stand still nearer than STOP_CM; slow down between the two
GAIN = 0.7  # percent of speed per point of reflected light off the edge
DAMPING = 1.5  # percent per point of change since the last reading


def clamp(value):
    return max(-100, min(100, value))


def speed_for(distance_cm):
    """How fast to go with the robot ahead this far away."""
    if distance_cm <= STOP_CM:
        return 0
    if distance_cm >= FREE_CM:
        return TOP_SPEED
    return TOP_SPEED * (distance_cm - STOP_CM) / (FREE_CM - STOP_CM)


tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
sonar = UltrasonicSensor(INPUT_4)

last_error = 0
while True:
    speed = speed_for(sonar.distance_centimeters)
    if speed == 0:
        tank.off(brake=True)
        continue
    error = eye.reflected_light_intensity - EDGE  # > 0: too much floor, the line is to the right
    turn = (GAIN * error + DAMPING * (error - last_error)) * speed / TOP_SPEED
    last_error = error
    tank.on(SpeedPercent(clamp(speed + turn)), SpeedPercent(clamp(speed - turn)))
