"""FakeSysfs serves a folder tree to the shim as a sysfs would, so upstream's fake-sys tests can run on it."""

import errno

import pytest

import ev3dev2
from ev3dev2 import Device, DeviceNotFound, _link
from ev3dev2.motor import OUTPUT_A, LargeMotor

from .fake_sysfs import FakeSysfs


def device_folder(root, class_name, name, **attributes):
    folder = root / class_name / name
    folder.mkdir(parents=True)
    for attribute, text in attributes.items():
        (folder / attribute).write_text(text + "\n")
    return folder


@pytest.fixture
def sysfs(tmp_path):
    device_folder(
        tmp_path,
        "tacho-motor",
        "motor0",
        address="ev3-ports:outA",
        driver_name="lego-ev3-l-motor",
        max_speed="1050",
        count_per_rot="360",
        speed_sp="0",
        position="7",
        command="",
    )
    device_folder(tmp_path, "tacho-motor", "motor1", address="ev3-ports:outB", driver_name="lego-ev3-m-motor")
    _link.connect(FakeSysfs(str(tmp_path)))
    yield tmp_path
    _link.disconnect()


def test_devices_are_the_folders_of_a_class_matched_by_name_and_by_what_an_attribute_contains(sysfs):
    backend = FakeSysfs(str(sysfs))

    assert backend.list_device_names("tacho-motor", "motor*", {}) == ["motor0", "motor1"]
    assert backend.list_device_names("tacho-motor", "motor*", {"address": "outB"}) == ["motor1"]
    assert backend.list_device_names("tacho-motor", "*", {"driver_name": ["x", "m-motor"]}) == ["motor1"]
    assert backend.list_device_names("tacho-motor", "*", {"no_such_attribute": ""}) == []
    assert backend.list_device_names("lego-sensor", "*", {}) == []
    assert Device("tacho-motor", address="outB").device_index == 1


def test_a_read_gives_the_file_and_a_missing_attribute_is_enoent(sysfs):
    motor = LargeMotor(OUTPUT_A)

    assert motor.position == 7
    assert _link.read("tacho-motor", "motor0", "driver_name") == "lego-ev3-l-motor\n"
    with pytest.raises(OSError) as error:
        _link.read("tacho-motor", "motor0", "duty_cycle")
    assert error.value.errno == errno.ENOENT
    with pytest.raises(DeviceNotFound):
        _ = motor.duty_cycle


def test_a_write_replaces_the_value_and_creates_no_attribute(sysfs):
    motor = LargeMotor(OUTPUT_A)

    motor.speed_sp = 500
    motor.speed_sp = 7

    assert (sysfs / "tacho-motor" / "motor0" / "speed_sp").read_text() == "7\n"
    assert motor.speed_sp == 7
    with pytest.raises(OSError) as error:
        _link.write("tacho-motor", "motor0", "time_sp", "100")
    assert error.value.errno == errno.ENOENT
    assert not (sysfs / "tacho-motor" / "motor0" / "time_sp").exists()


def test_a_command_is_stored_and_moves_nothing_as_in_fake_sys(sysfs):
    motor = LargeMotor(OUTPUT_A)

    motor.run_forever(speed_sp=100)

    assert motor._get_attribute(None, "command")[1] == "run-forever"
    assert motor.position == 7


def test_without_a_root_it_serves_wherever_device_root_path_points(sysfs, monkeypatch):
    monkeypatch.setattr(ev3dev2.Device, "DEVICE_ROOT_PATH", str(sysfs))
    _link.connect(FakeSysfs())

    assert LargeMotor(OUTPUT_A).driver_name == "lego-ev3-l-motor"


def test_there_are_no_brick_features_beyond_attributes(sysfs):
    with pytest.raises(NotImplementedError, match="sound"):
        _link.call("sound", "beep")
