"""A brick checks writes itself (brick/link.py check_write) with the rules the devices publish
(Device.write_rules): for every device and rule, it must refuse exactly what the device refuses,
or a program would see an error the simulator never raised (or miss one)."""

from types import SimpleNamespace

import pytest

from ev3sim2d.brick.link import check_write
from ev3sim2d.devices.brick_parts import Led
from ev3sim2d.devices.motor import TachoMotor
from ev3sim2d.devices.registry import SENSORS

VALUES = [
    "0",
    "1",
    "-1",
    " 42 ",
    "42\n",
    "+7",
    "1_000",
    "1050",
    "1051",
    "-1050",
    "-1051",
    "100",
    "101",
    "-101",
    "60000",
    "60001",
    "99999999999999999999",
    "",
    " ",
    "abc",
    "1.5",
    "0x10",
    "٣",
    "run-forever",
    " run-forever ",
    "RUN-FOREVER",
    "stop",
    "reset",
    "coast",
    "brake",
    "hold",
    "normal",
    "inversed",
    "COL-REFLECT",
    "COL-COLOR",
    "US-DIST-CM",
    "GYRO-ANG",
    "none",
    "timer",
    "255",
    "256",
]


def devices():
    motors = [TachoMotor("ev3-ports:outA", "large"), TachoMotor("ev3-ports:outB", "medium")]
    spec = SimpleNamespace(radius_cm=5.0, angle_deg=0.0, aim_deg=0.0, noise=0.0, facing="forward", options={})
    around = SimpleNamespace(heading_rad=0.0, tick=0, sound_until_tick=0)
    floor = SimpleNamespace(
        cell_cm=10.0, width=1, height=1, reflected=[[50]], color_id=[[6]], raw_rgb=[[(1, 1, 1)]]
    )
    sensors = [
        kind("ev3-ports:in1", spec, around, floor)
        if "floor" in kind.__init__.__code__.co_varnames
        else kind("ev3-ports:in1", spec, around)
        for kind in SENSORS.values()
    ]
    return [*motors, *sensors, Led("led0:green:brick-status")]


def cases():
    for device in devices():
        for attribute, rule in device.write_rules.items():
            yield pytest.param(device, attribute, rule, id=f"{type(device).__name__}-{attribute}")


@pytest.mark.parametrize("device,attribute,rule", list(cases()))
def test_the_brick_refuses_exactly_what_the_device_refuses(device, attribute, rule):
    for value in VALUES:
        try:
            device.write(attribute, value)
            device_error = None
        except OSError as err:
            device_error = err.errno
        try:
            check_write(rule, value)
            brick_error = None
        except OSError as err:
            brick_error = err.errno
        assert brick_error == device_error, (
            f"{attribute}={value!r}: device {device_error}, brick {brick_error}"
        )
