"""Outside a simulated run the shim imports cleanly, and using a device says how to run the program."""

import importlib
import inspect
import os
import subprocess
import sys
from pathlib import Path

import pytest

import ev3dev2
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

# Every module of the shim, found on disk (the private link module too).
MODULES = sorted(
    ".".join(path.relative_to(REPO).with_suffix("").parts).removesuffix(".__init__")
    for path in Path(REPO, "ev3dev2").rglob("*.py")
)


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


# What a class needs besides defaults to be built (ports; a wheel and a track for MoveDifferential).
ARGUMENTS = {
    "Device": ("tacho-motor",),
    "MotorSet": ({OUTPUT_A: LargeMotor, OUTPUT_B: LargeMotor},),
    "MoveDifferential": (OUTPUT_A, OUTPUT_B, EV3Tire, 120),
}


def device_classes():
    """Every public class of the shim that stands for hardware: devices, motor sets, LEDs, buttons, the LCD."""
    from ev3dev2.button import ButtonEVIO
    from ev3dev2.display import FbMem
    from ev3dev2.motor import MotorSet

    found = {}
    for name in MODULES:
        module = importlib.import_module(name)
        for cls_name, cls in vars(module).items():
            if (
                inspect.isclass(cls)
                and not cls_name.startswith("_")
                and cls.__module__ == name
                and issubclass(cls, (ev3dev2.Device, MotorSet, Leds, ButtonEVIO, FbMem))
            ):
                found[f"{name}.{cls_name}"] = cls
    return found


DEVICE_CLASSES = device_classes()


def test_every_device_class_is_found():
    some = {
        "ev3dev2.motor.MoveTank",
        "ev3dev2.sensor.lego.GyroSensor",
        "ev3dev2.control.rc_tank.RemoteControlledTank",
    }
    assert some <= set(DEVICE_CLASSES)
    assert len(DEVICE_CLASSES) >= 30, sorted(DEVICE_CLASSES)


@pytest.mark.parametrize("name", sorted(DEVICE_CLASSES))
def test_constructing_any_device_outside_a_run_raises_not_in_simulation(name):
    cls = DEVICE_CLASSES[name]
    arguments = ARGUMENTS.get(cls.__name__, (OUTPUT_A, OUTPUT_B) if issubclass(cls, MoveTank) else ())
    assert not _link.connected()
    with pytest.raises(_link.NotInSimulation, match="must run inside the simulator: ev3sim2d run"):
        cls(*arguments)
