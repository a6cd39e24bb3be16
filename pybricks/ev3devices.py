"""LEGO MINDSTORMS EV3 motors and sensors (pybricks.ev3devices, Pybricks 2.0).

Motor is in _motor.py and the sensors in _ev3_sensors.py; this module gathers them under the firmware's
names (bricks/ev3dev/modules/pybricks/ev3devices.py).
"""

from ._ev3_sensors import ColorSensor, GyroSensor, InfraredSensor, TouchSensor, UltrasonicSensor
from ._motor import Motor

__all__ = ["Motor", "TouchSensor", "ColorSensor", "InfraredSensor", "UltrasonicSensor", "GyroSensor"]
