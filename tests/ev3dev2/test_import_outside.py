"""Outside a simulated run the shim imports cleanly, and using a device says how to run the program."""

import os
import subprocess
import sys

import pytest

from ev3dev2 import _link
from ev3dev2.button import Button
from ev3dev2.display import Display
from ev3dev2.led import Led, Leds
from ev3dev2.motor import (
    OUTPUT_A,
    OUTPUT_B,
    DcMotor,
    LargeMotor,
    MediumMotor,
    Motor,
    MoveDifferential,
    MoveJoystick,
    MoveSteering,
    MoveTank,
    ServoMotor,
    list_motors,
)
from ev3dev2.port import LegoPort
from ev3dev2.power import PowerSupply
from ev3dev2.sensor import I2cSensor, Sensor, list_sensors
from ev3dev2.sensor.lego import (
    ColorSensor,
    GyroSensor,
    InfraredSensor,
    LightSensor,
    SoundSensor,
    TouchSensor,
    UltrasonicSensor,
)
from ev3dev2.sound import Sound
from ev3dev2.wheel import EV3Tire

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

MODULES = [
    "ev3dev2",
    "ev3dev2._platform.ev3",
    "ev3dev2.auto",
    "ev3dev2.button",
    "ev3dev2.console",
    "ev3dev2.control",
    "ev3dev2.display",
    "ev3dev2.fonts",
    "ev3dev2.led",
    "ev3dev2.motor",
    "ev3dev2.port",
    "ev3dev2.power",
    "ev3dev2.sensor",
    "ev3dev2.sensor.lego",
    "ev3dev2.sound",
    "ev3dev2.stopwatch",
    "ev3dev2.unit",
    "ev3dev2.version",
    "ev3dev2.wheel",
]


def test_every_module_imports_in_a_fresh_interpreter_without_a_simulator():
    code = f"import importlib\nfor name in {MODULES!r}:\n    importlib.import_module(name)\n"
    code += "from ev3dev2 import _link\nassert not _link.connected()\nfrom ev3dev2.auto import *\nprint(OUTPUT_A, INPUT_1)"
    result = subprocess.run(
        [sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=60
    )

    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "ev3-ports:outA ev3-ports:in1"


@pytest.mark.parametrize(
    "make",
    [
        lambda: Motor(OUTPUT_A),
        lambda: LargeMotor(OUTPUT_A),
        lambda: MediumMotor(),
        lambda: DcMotor(),
        lambda: ServoMotor(),
        lambda: MoveTank(OUTPUT_A, OUTPUT_B),
        lambda: MoveSteering(OUTPUT_A, OUTPUT_B),
        lambda: MoveJoystick(OUTPUT_A, OUTPUT_B),
        lambda: MoveDifferential(OUTPUT_A, OUTPUT_B, EV3Tire, 120),
        lambda: list(list_motors()),
        lambda: Sensor(),
        lambda: I2cSensor(),
        lambda: list(list_sensors()),
        lambda: TouchSensor(),
        lambda: ColorSensor(),
        lambda: UltrasonicSensor(),
        lambda: GyroSensor(),
        lambda: InfraredSensor(),
        lambda: SoundSensor(),
        lambda: LightSensor(),
        lambda: Led(),
        lambda: Leds(),
        lambda: Button(),
        lambda: Display(),
        lambda: PowerSupply(),
        lambda: LegoPort(),
        lambda: Sound().beep(),
        lambda: Sound().speak("hello"),
    ],
)
def test_using_a_device_outside_a_run_raises_not_in_simulation(make):
    assert not _link.connected()
    with pytest.raises(_link.NotInSimulation, match="must run inside the simulator"):
        make()
