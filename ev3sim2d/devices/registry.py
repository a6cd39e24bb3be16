"""Device kinds by the names robot files use: a new kind of device is one new file and one line here."""

from __future__ import annotations

from .color import ColorSensor
from .gyro import GyroSensor
from .infrared import InfraredSensor
from .motor import KINDS as MOTOR_KINDS
from .nxt_light import NxtLightSensor
from .nxt_sound import NxtSoundSensor
from .touch import TouchSensor
from .ultrasonic import UltrasonicSensor

SENSORS = {
    "touch": TouchSensor,
    "gyro": GyroSensor,
    "color": ColorSensor,
    "ultrasonic": UltrasonicSensor,
    "infrared": InfraredSensor,
    "nxt-light": NxtLightSensor,
    "nxt-sound": NxtSoundSensor,
}
MOTORS = tuple(MOTOR_KINDS)
