"""Device: finding devices, attribute access through _link, and upstream's errors."""

import errno

import pytest

import ev3dev2
from ev3dev2 import Device, DeviceNotFound, _link, list_device_names, list_devices
from ev3dev2.motor import OUTPUT_D, LargeMotor, MediumMotor, Motor

from .fake_brick import sensor, tacho_motor


def test_platform_is_always_ev3():
    assert ev3dev2.get_current_platform() == "ev3"
    assert ev3dev2.is_micropython() is False
    assert ev3dev2.__version__ == "2.1.0"


def test_device_is_found_by_name_pattern_and_attributes(make_brick):
    make_brick(tacho_motor("motor0", "outA"), tacho_motor("motor3", "outB", driver_name="lego-ev3-m-motor"))

    device = Device("tacho-motor", address="outB")

    assert device.device_index == 3
    assert device._device_name == "motor3"
    assert str(device) == "Device(outB)"
    assert Device("tacho-motor", "motor*", driver_name=["lego-ev3-m-motor", "x"]).device_index == 3


def test_device_index_takes_only_the_last_digit_as_upstream():
    assert Device("tacho-motor", "motor12", name_exact=True).device_index == 2


def test_missing_device_raises_device_not_found_with_upstream_message(make_brick):
    make_brick(tacho_motor("motor0", "outA"))

    with pytest.raises(DeviceNotFound) as error:
        LargeMotor("outD")
    assert str(error.value) == "LargeMotor(outD) is not connected."
    assert error.value.__cause__ is None and error.value.__suppress_context__

    with pytest.raises(DeviceNotFound, match=r"^LargeMotor\(ev3-ports:outD\) is not connected\.$"):
        LargeMotor(OUTPUT_D)
    with pytest.raises(DeviceNotFound, match=r"^MediumMotor\(outA\) is not connected\.$"):
        MediumMotor("outA")
    with pytest.raises(DeviceNotFound, match=r"^Motor is not connected\.$"):
        Motor(driver_name="nothing-like-it")


def test_attribute_reads_are_stripped_and_writes_are_strings(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA", polarity="inversed"))
    motor = Motor("outA")

    assert motor.polarity == "inversed"
    motor.position = 12.7
    assert brick.writes() == [("motor0", "position", "12")]


def test_cached_attributes_are_read_once_per_device(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA"))
    motor = Motor("outA")
    assert brick.reads() == [("motor0", "max_speed"), ("motor0", "count_per_rot")]
    brick.clear_log()

    for _ in range(3):
        assert motor.max_speed == 1050
        assert motor.count_per_rot == 360
        assert motor.commands == [
            "run-forever",
            "run-to-abs-pos",
            "run-to-rel-pos",
            "run-timed",
            "run-direct",
            "stop",
            "reset",
        ]
        assert motor.driver_name == "lego-ev3-l-motor"
        assert motor.stop_actions == ["coast", "brake", "hold"]
        _ = motor.position

    assert (
        brick.reads()
        == [("motor0", "commands"), ("motor0", "driver_name"), ("motor0", "stop_actions")]
        + [("motor0", "position")] * 3
    )


def test_set_and_from_set_attributes(make_brick):
    make_brick(tacho_motor("motor0", "outA", state="running [holding] stalled"))
    motor = Motor("outA")

    assert motor.state == ["running", "holding", "stalled"]
    assert motor.get_attr_from_set(None, "state") == "holding"
    assert motor.is_running and motor.is_holding and motor.is_stalled and not motor.is_ramping


def test_missing_attribute_means_the_device_is_no_longer_connected(make_brick):
    make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor("outA")

    with pytest.raises(DeviceNotFound, match=r"^LargeMotor\(outA\) is no longer connected$") as error:
        _ = motor.count_per_m
    assert isinstance(error.value.__cause__, OSError) and error.value.__cause__.errno == errno.ENOENT


def test_out_of_range_speed_sp_names_the_max_speed(make_brick):
    make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor("outA")

    with pytest.raises(ValueError) as error:
        motor.speed_sp = 2000
    assert str(error.value) == "The given speed value b'2000' was out of range. Max speed: +/-1050"


def test_other_invalid_values_give_upstreams_generic_message(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor("outA")

    def refuse(class_name, name, attribute, value):
        raise OSError(errno.EINVAL, "Invalid argument")

    brick.write = refuse
    _link.connect(brick)  # the link binds the backend's methods when it connects
    with pytest.raises(
        ValueError, match=r"^One or more arguments were out of range or invalid, value b'bogus'$"
    ):
        motor.stop_action = "bogus"


def test_write_only_and_read_only_attributes(make_brick):
    make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor("outA")

    with pytest.raises(Exception, match="^command is a write-only property!$"):
        _ = motor.command
    with pytest.raises(AttributeError):
        motor.speed = 10
    with pytest.raises(AttributeError):  # __slots__, as upstream: a misspelt attribute is an error
        motor.sped_sp = 10


def test_list_device_names_and_list_devices(make_brick):
    make_brick(
        tacho_motor("motor0", "outA"), tacho_motor("motor1", "outB"), sensor("sensor0", "in1", "lego-ev3-us")
    )

    assert list(list_device_names("/sys/class/tacho-motor", "*")) == ["motor0", "motor1"]
    assert list(list_device_names("/sys/class/tacho-motor", "*", address=["outB", "outC"])) == ["motor1"]
    devices = list(list_devices("lego-sensor", "sensor*"))
    assert [d.device_index for d in devices] == [0]
    assert [m.address for m in ev3dev2.motor.list_motors()] == ["ev3-ports:outA", "ev3-ports:outB"]


def test_devices_sort_by_name(make_brick):
    make_brick(tacho_motor("motor0", "outA"), tacho_motor("motor1", "outB"))
    assert sorted([LargeMotor("outB"), LargeMotor("outA")])[0].kwargs["address"] == "outA"
