"""The LEGO sensors: mode switching, scaling and the readings built from raw values."""

import pytest

from ev3dev2.sensor import INPUT_1, INPUT_2, Sensor, list_sensors
from ev3dev2.sensor.lego import (
    ColorSensor,
    GyroSensor,
    InfraredSensor,
    LightSensor,
    SoundSensor,
    TouchSensor,
    UltrasonicSensor,
)

from .fake_brick import sensor


def test_reading_switches_the_mode_only_when_needed(make_brick):
    brick = make_brick(sensor("sensor0", "in1", "lego-ev3-color", mode="COL-COLOR", value0="42"))
    cs = ColorSensor(INPUT_1)

    assert cs.reflected_light_intensity == 42
    assert cs.reflected_light_intensity == 42
    assert brick.log == [
        ["read", "sensor0", "mode"],
        ["write", "sensor0", "mode", "COL-REFLECT"],
        ["read", "sensor0", "value0"],
        ["read", "sensor0", "mode"],
        ["read", "sensor0", "value0"],
    ]


def test_sensors_are_matched_by_driver(make_brick):
    make_brick(sensor("sensor0", "in1", "lego-ev3-touch"), sensor("sensor1", "in2", "lego-ev3-color"))

    assert ColorSensor().address == "ev3-ports:in2"
    assert TouchSensor().address == "ev3-ports:in1"
    assert [s.driver_name for s in list_sensors()] == ["lego-ev3-touch", "lego-ev3-color"]
    with pytest.raises(Exception, match=r"^GyroSensor is not connected\.$"):
        GyroSensor()
    with pytest.raises(Exception, match=r"^ColorSensor\(ev3-ports:in1\) is not connected\.$"):
        ColorSensor(INPUT_1)


def test_color_names_and_components(make_brick):
    make_brick(sensor("sensor0", "in1", "lego-ev3-color", value0=["5", "10"], value1="150", value2="300"))
    cs = ColorSensor()

    assert cs.color_name == "Red"
    assert cs.raw == (10, 150, 300)
    assert cs.rgb == (8, 127, 255)
    assert (cs.red, cs.green, cs.blue) == (10, 150, 300)
    cs.calibrate_white()
    assert (cs.red_max, cs.green_max, cs.blue_max) == (10, 150, 300)
    assert cs.rgb == (255, 255, 255)
    assert cs.hsv == (0.0, 0.0, 255)
    assert cs.COLORS[cs.COLOR_BROWN] == "Brown"


def test_color_spaces(make_brick):
    make_brick(sensor("sensor0", "in1", "lego-ev3-color", value0="300", value1="0", value2="0"))
    cs = ColorSensor()

    assert cs.rgb == (255, 0, 0)
    assert cs.hsv == (0.0, 1.0, 255)
    hue, lightness, saturation = cs.hls
    assert hue == 0.0 and lightness == 127.5
    L, a, b = cs.lab
    assert L > 0 and a > 0


def test_ultrasonic_scales_by_decimals_read_once_per_mode(make_brick):
    brick = make_brick(sensor("sensor0", "in4", "lego-ev3-us", value0="123", decimals="1"))
    us = UltrasonicSensor()

    assert us.distance_centimeters == pytest.approx(12.3)
    assert us.distance_centimeters == pytest.approx(12.3)
    assert brick.reads().count(("sensor0", "decimals")) == 1
    brick.clear_log()
    assert us.distance_centimeters_ping == pytest.approx(12.3)
    assert brick.log == [["write", "sensor0", "mode", "US-SI-CM"], ["read", "sensor0", "value0"]]
    assert us.other_sensor_present is True


def test_gyro_reads_its_angle_when_made_and_reset_writes_direct(make_brick):
    brick = make_brick(sensor("sensor0", "in2", "lego-ev3-gyro", value0=["7", "0"]))
    gyro = GyroSensor(INPUT_2)
    assert brick.log == [["read", "sensor0", "mode"], ["read", "sensor0", "value0"]]
    brick.clear_log()

    gyro.reset()

    assert brick.log == [
        ["write", "sensor0", "direct", "\x11"],
        ["read", "sensor0", "mode"],
        ["read", "sensor0", "value0"],
    ]
    assert gyro.circle_angle() == 90


@pytest.mark.parametrize("angle, circle", [(0, 90), (30, 60), (120, 330), (-30, 120), (-200, 290), (360, 90)])
def test_gyro_circle_angle_starts_at_90_and_grows_counter_clockwise(make_brick, angle, circle):
    make_brick(sensor("sensor0", "in2", "lego-ev3-gyro", value0=["0", str(angle)]))
    assert GyroSensor().circle_angle() == circle


def test_gyro_angle_and_rate_and_calibrate(make_brick):
    brick = make_brick(sensor("sensor0", "in2", "lego-ev3-gyro", value0="15", value1="-3"))
    gyro = GyroSensor()

    assert gyro.angle_and_rate == (15, -3)
    start = brick.clock
    brick.clear_log()
    gyro.calibrate()

    assert brick.clock - start == pytest.approx(2)
    assert brick.writes() == [("sensor0", "mode", "GYRO-CAL"), ("sensor0", "mode", "GYRO-G&A")]


def test_gyro_waits_until_the_angle_changed_by(make_brick):
    brick = make_brick(sensor("sensor0", "in2", "lego-ev3-gyro", value0=["0", "0", "-5", "20", "-40", "-95"]))
    gyro = GyroSensor()
    start = brick.clock

    gyro.wait_until_angle_changed_by(90)  # -5, 20 and -40 are too little: three 10 ms sleeps

    assert brick.clock - start == pytest.approx(0.03)
    with pytest.raises(AssertionError, match="^Gyro mode should be"):
        gyro.mode = "GYRO-RATE"
        gyro.wait_until_angle_changed_by(10)


def test_touch_sensor_waits_for_a_press(make_brick):
    brick = make_brick(sensor("sensor0", "in1", "lego-ev3-touch", value0=["0", "0", "1", "1", "0"]))
    touch = TouchSensor()
    start = brick.clock

    assert touch.wait_for_pressed() is True
    assert brick.clock - start == pytest.approx(0.02)
    assert touch.is_pressed == 1
    assert touch.is_released is True
    assert touch.wait_for_pressed(timeout_ms=100) is False


def test_touch_sensor_bump(make_brick):
    make_brick(sensor("sensor0", "in1", "lego-ev3-touch", value0=["0", "1", "1", "0"]))
    assert TouchSensor().wait_for_bump(timeout_ms=1000) is True


def test_infrared_proximity_beacon_and_remote(make_brick):
    make_brick(sensor("sensor0", "in3", "lego-ev3-ir", value0="4", value1="9", value2="-12", value3="-128"))
    ir = InfraredSensor()

    assert ir.proximity == 4
    assert ir.heading_and_distance() == (4, 9)
    assert ir.heading(2) == -12
    assert ir.distance(2) is None
    assert ir.buttons_pressed(1) == ["bottom_right"]
    assert ir.bottom_right(1) and not ir.top_left(1)
    assert ir.buttons_pressed(2) == ["beacon"] and ir.beacon(2)
    assert ir.buttons_pressed(3) == []  # value2 is -12, no button code
    assert ir.mode == "IR-REMOTE"
    with pytest.raises(AssertionError, match="^channel is 5, it must be 1, 2, 3, or 4$"):
        ir.heading(5)


def test_infrared_process_calls_the_button_handlers(make_brick):
    make_brick(sensor("sensor0", "in3", "lego-ev3-ir", mode="IR-REMOTE", value0=["1", "0"]))
    ir = InfraredSensor()
    events = []
    ir.on_channel1_top_left = lambda state: events.append(("top_left", state))
    ir.on_change = events.append

    ir.process()
    ir.process()

    # upstream reports every change to on_change as False (it looks for the name among (name, channel) pairs)
    assert events == [
        ("top_left", True),
        [("top_left", 1, False)],
        ("top_left", False),
        [("top_left", 1, False)],
    ]


def test_generic_sensor_values_and_bin_data(make_brick):
    brick = make_brick(
        sensor(
            "sensor0",
            "in1",
            "lego-ev3-us",
            value2="17",
            num_values="2",
            bin_data_format="s16",
            bin_data="\x01\x00\xff\xff",
            units="cm",
        )
    )
    s = Sensor(INPUT_1)

    assert s.value(2) == 17
    assert s.units == "cm"
    assert s.modes == ["US-DIST-CM", "US-DIST-IN", "US-LISTEN", "US-SI-CM", "US-SI-IN"]
    assert s.bin_data() == bytearray(b"\x01\x00\xff\xff")
    assert s.bin_data("<hh") == (1, -1)
    assert [r for r in brick.reads() if r[1] in ("bin_data_format", "num_values")] == [
        ("sensor0", "bin_data_format"),
        ("sensor0", "num_values"),
    ]


def test_nxt_sound_and_light_sensors_scale_their_values(make_brick):
    make_brick(
        sensor("sensor0", "in1", "lego-nxt-sound", mode="DB", value0="512", decimals="1"),
        sensor("sensor1", "in2", "lego-nxt-light", mode="REFLECT", value0="456", decimals="1"),
    )
    assert SoundSensor().sound_pressure == pytest.approx(51.2)
    assert LightSensor().reflected_light_intensity == pytest.approx(45.6)
