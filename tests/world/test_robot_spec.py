"""Robot descriptions: the shipped EV3 driving base, port names, and mistakes reported with their line."""

import textwrap

import pytest

from ev3sim2d.world.robot_spec import (
    MOTOR_PORTS,
    SENSOR_PORTS,
    default_robot,
    load_robot,
    normalise_port,
    parse_robot,
    shipped_robot_names,
    shipped_robots_dir,
)
from ev3sim2d.world.source_error import WorldFileError

BASE = """\
name: test bot
wheel_diameter_mm: 56
axle_track_mm: 120
body: {front_cm: 9, back_cm: 7, width_cm: 15}
motors:
  - {port: B, kind: large, wheel: left}
  - {port: C, kind: large, wheel: right}
"""
# BASE is 7 lines; a `sensors:` section added after it starts on line 8.


def robot_error(text: str) -> WorldFileError:
    with pytest.raises(WorldFileError) as info:
        parse_robot(textwrap.dedent(text), "bot.yaml")
    assert info.value.path == "bot.yaml"
    return info.value


def test_default_robot_is_the_ev3_driving_base():
    robot = default_robot()
    assert robot.name == "EV3 driving base"
    assert (robot.wheel_diameter_mm, robot.axle_track_mm) == (56, 120)
    assert robot.wheel_radius_cm == pytest.approx(2.8) and robot.axle_track_cm == pytest.approx(12)
    assert 14 <= robot.body.length_cm <= 20 and 12 <= robot.body.width_cm <= 16
    assert robot.left_wheel == robot.motor("B") and robot.left_wheel.kind == "large"
    assert robot.right_wheel == robot.motor("outC") and robot.right_wheel.kind == "large"
    assert robot.motor("A").kind == "medium" and robot.motor("A").wheel is None
    assert robot.motor("D") is None


def test_default_robot_sensors_sit_where_the_driving_base_has_them():
    robot = default_robot()
    touch, gyro, color, ultrasonic = (robot.sensor(p) for p in ("1", "in2", "3", "ev3-ports:in4"))
    assert (touch.kind, touch.angle_deg, touch.radius_cm, touch.facing) == (
        "touch",
        0,
        robot.body.front_cm,
        "forward",
    )
    assert (gyro.kind, gyro.angle_deg, gyro.radius_cm, gyro.facing) == ("gyro", 180, 3, "down")
    assert (color.kind, color.radius_cm, color.facing, color.options) == (
        "color",
        7,
        "down",
        {"spot_cm": 1.5},
    )
    assert (ultrasonic.kind, ultrasonic.radius_cm, ultrasonic.facing) == ("ultrasonic", 8, "forward")
    assert ultrasonic.options["cone_deg"] == 15
    assert color.offset_cm == pytest.approx((7, 0))
    assert gyro.offset_cm == pytest.approx((-3, 0))
    assert all(sensor.noise == 0 for sensor in robot.sensors)


def test_default_robot_is_read_once_and_each_caller_gets_its_own_copy():
    first, second = default_robot(), default_robot()
    assert first == second and first is not second
    first.sensor("3").options["spot_cm"] = 99
    assert default_robot().sensor("3").options["spot_cm"] == 1.5
    assert "ev3-driving-base" in shipped_robot_names()
    assert load_robot(shipped_robots_dir() / "ev3-driving-base.yaml") == default_robot()


@pytest.mark.parametrize(
    ("written", "ports", "port"),
    [
        ("B", MOTOR_PORTS, "outB"),
        ("outb", MOTOR_PORTS, "outB"),
        ("ev3-ports:outD", MOTOR_PORTS, "outD"),
        ("3", SENSOR_PORTS, "in3"),
        (3, SENSOR_PORTS, "in3"),
        ("IN1", SENSOR_PORTS, "in1"),
        ("outE", MOTOR_PORTS, None),
        ("in5", SENSOR_PORTS, None),
        ("B", SENSOR_PORTS, None),
    ],
)
def test_port_names(written, ports, port):
    assert normalise_port(written, ports) == port


def test_kind_specific_options_get_defaults_and_sensors_can_look_sideways():
    robot = parse_robot(
        BASE
        + "sensors:\n"
        + "  - {port: 4, kind: ultrasonic, angle_deg: 90, radius_cm: 6, aim_deg: 90, noise: 0.5}\n"
        + "  - {port: 1, kind: infrared, max_cm: 50}\n"
        + "  - {port: 2, kind: color}\n"
    )
    side = robot.sensor("4")
    assert (side.facing, side.aim_deg, side.noise) == ("forward", 90, 0.5)
    assert side.options == {"cone_deg": 15, "max_cm": 255}
    assert side.offset_cm == pytest.approx((0, 6))
    assert robot.sensor("1").options == {"cone_deg": 30, "max_cm": 50}
    assert robot.sensor("2").facing == "down" and robot.sensor("2").options == {"spot_cm": 1.5}


def test_robot_colour_may_be_a_name_hex_or_rgb():
    assert parse_robot(BASE + "color: red\n").color == (210, 40, 40)
    assert parse_robot(BASE + "color: '#0a0B0c'\n").color == (10, 11, 12)
    assert parse_robot(BASE + "color: [1, 2, 3]\n").color == (1, 2, 3)


@pytest.mark.parametrize(
    ("text", "line", "words"),
    [
        (
            BASE + "sensors:\n  - {port: in5, kind: touch}\n",
            9,
            ["unknown sensor port 'in5'", "in1, in2, in3, in4"],
        ),
        (BASE + "sensors:\n  - {port: B, kind: touch}\n", 9, ["sensors plug into input ports", "in1"]),
        (BASE + "motors2: []\n", 8, ["unknown key 'motors2'", "did you mean 'motors'"]),
        (
            BASE + "sensors:\n  - port: 3\n    kind: colour\n",
            10,
            ["unknown kind 'colour'", "did you mean 'color'"],
        ),
        (
            BASE + "sensors:\n  - {port: 3, kind: color, facing: up}\n",
            9,
            ["unknown facing 'up'", "forward, down"],
        ),
        (  # a sensor facing a way its device does not model is refused, never read from the floor
            BASE + "sensors:\n  - {port: 4, kind: ultrasonic, facing: down}\n",
            9,
            ["ultrasonic sensor facing down", "does not model", "facing: forward"],
        ),
        (
            BASE + "sensors:\n  - {port: 4, kind: infrared, facing: down}\n",
            9,
            ["infrared sensor facing down"],
        ),
        (BASE + "sensors:\n  - {port: 1, kind: touch, facing: down}\n", 9, ["touch sensor facing down"]),
        (
            BASE + "sensors:\n  - {port: 3, kind: color, cone_deg: 5}\n",
            9,
            ["unknown key 'cone_deg'", "spot_cm"],
        ),
        (BASE + "sensors:\n  - {port: 3, kind: color, noise: -1}\n", 9, ["cannot be negative"]),
        (
            BASE + "sensors:\n  - {port: 3, kind: color, aim_deg: 90}\n",
            9,
            ["'aim_deg' turns a sensor that faces forward"],
        ),
        (BASE + "sensors:\n  - {port: 3}\n", 9, ["missing key 'kind'"]),
        (
            BASE + "sensors:\n  - {port: 3, kind: color}\n  - {port: in3, kind: touch}\n",
            10,
            ["port in3 already has a device (line 9)"],
        ),
        (BASE + "  - {port: outB, kind: medium}\n", 8, ["port outB already has a device (line 6)"]),
        (
            BASE + "  - {port: D, kind: large, wheel: left}\n",
            8,
            ["two motors drive the left wheel", "line 6"],
        ),
        (BASE.replace("wheel: right", "wheel: rihgt"), 7, ["unknown wheel 'rihgt'", "did you mean 'right'"]),
        (BASE.replace(", wheel: right", ""), 6, ["no motor drives the right wheel", "wheel: right"]),
        (
            BASE.replace("kind: large, wheel: left", "kind: huge, wheel: left"),
            6,
            ["unknown kind 'huge'", "large, medium"],
        ),
        (BASE.replace("port: B,", "port: 2,"), 6, ["motors plug into output ports"]),
        (
            BASE.replace("wheel_diameter_mm: 56", "wheel_diameter_mm: 56mm"),
            2,
            ["must be a number (mm), got '56mm'"],
        ),
        (BASE.replace("axle_track_mm: 120", "axle_track_mm: 0"), 3, ["50 to 500 mm"]),
        (BASE.replace("width_cm: 15", "width: 15"), 4, ["unknown key 'width'", "width_cm"]),
        (BASE.replace("axle_track_mm: 120\n", ""), 1, ["missing key 'axle_track_mm'", "axle_track_mm: 120"]),
        (BASE + "color: pinkish\n", 8, ["'color' must be a colour name"]),
        ("name: [x\n", 2, ["YAML syntax error"]),
    ],
)
def test_mistakes_in_a_robot_file_name_their_line(text, line, words):
    err = robot_error(text)
    assert err.line == line, str(err)
    for word in words:
        assert word in err.message, str(err)
