"""A robot description: wheels, body box, and which motor or sensor sits on which port, read from YAML.

Robot frame: the origin is the robot centre (midway between the two driving
wheels), +x points forward, +y to the left.  A sensor sits `radius_cm` from the
centre in direction `angle_deg` (0 = straight ahead, 90 = left), and looks
either `down` at the floor or `forward` (turned `aim_deg` from the robot's
heading, 90 = to the left).  See docs/world-files.md for the file format.
Which kinds of sensor there are, and the facings and options each allows, their device classes say
(devices/registry.py; a kind of one's own: docs/devices.md).
"""

from __future__ import annotations

import copy
import difflib
import functools
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .colors import EV3_COLORS
from .file_limits import (
    ANGLE_DEG,
    AXLE_TRACK_MM,
    BODY_MIN_CM,
    BODY_REACH_CM,
    LIMITS_DEG,
    MAX_MOTORS,
    MAX_NAME_CHARS,
    MAX_SENSORS,
    NOISE,
    ROBOT_FILE,
    SENSOR_REACH_PAST_BODY_CM,
    WHEEL_DIAMETER_MM,
    sensor_option_range,
    within,
)
from .source_error import WorldFileError
from .yaml_source import Fields, Node, load_yaml_text, read_text_file

MOTOR_PORTS = ("outA", "outB", "outC", "outD")
SENSOR_PORTS = ("in1", "in2", "in3", "in4")
FACINGS = ("forward", "down")
WHEELS = ("left", "right")
MOUNTINGS = ("normal", "reversed")


def _sensor_classes():
    """The devices' registry: which kinds of sensor exist and what each allows is said by its class (kind,
    facings, options: devices/sensor.py), so a new kind is one device file.  Imported when a robot is read,
    not with this module: the devices import the world's colours."""
    from ..devices import registry

    return registry


def __getattr__(name: str):
    """The kind tables this module once kept, now read from the device classes (for older callers)."""
    if name == "SENSOR_KINDS":
        return _sensor_classes().sensor_kinds()
    if name == "MOTOR_KINDS":
        return _sensor_classes().MOTORS
    if name == "SENSOR_OPTIONS":
        return {kind: dict(cls.OPTIONS) for kind, cls in _sensor_classes().SENSORS.items()}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


DEFAULT_ROBOT_COLOR = (230, 170, 30)
"""Body colour to draw when a robot file gives none (LEGO yellow)."""


@dataclass(frozen=True)
class MotorSpec:
    """A motor on an output port; `wheel` says which driving wheel it turns, if any.

    `reversed`: the motor is mounted the other way round, so with normal polarity a positive
    speed turns its wheel backwards (a program for such a robot sets `polarity = 'inversed'`).
    A motor that drives no wheel (an arm, a gripper) may meet end stops, `limits_deg` (low, high:
    degrees from where its shaft starts, positive the way a positive speed turns it with normal
    polarity), and a load, `load_pct` (a torque against its turning, in % of the motor's stall
    torque: devices/motor.py, TachoMotor.turn_free).
    """

    port: str
    kind: str
    wheel: str | None = None
    reversed: bool = False
    limits_deg: tuple[float, float] | None = None
    load_pct: float = 0.0


@dataclass(frozen=True)
class SensorSpec:
    """A sensor on an input port, placed in the robot frame; `noise` is a standard deviation in its own unit."""

    port: str
    kind: str
    angle_deg: float = 0.0
    radius_cm: float = 0.0
    facing: str = "down"
    noise: float = 0.0
    options: dict[str, float] = field(default_factory=dict)
    aim_deg: float = 0.0

    @property
    def offset_cm(self) -> tuple[float, float]:
        """(x, y) of the sensor in the robot frame (x forward, y left)."""
        a = math.radians(self.angle_deg)
        return (self.radius_cm * math.cos(a), self.radius_cm * math.sin(a))


@dataclass(frozen=True)
class BodySpec:
    """The robot's footprint: a box reaching `front_cm` ahead of and `back_cm` behind the centre, `width_cm` wide."""

    front_cm: float
    back_cm: float
    width_cm: float

    @property
    def length_cm(self) -> float:
        return self.front_cm + self.back_cm

    def corners_cm(self) -> list[tuple[float, float]]:
        """The box corners in the robot frame, counter-clockwise from front-left."""
        half = self.width_cm / 2
        return [(self.front_cm, half), (-self.back_cm, half), (-self.back_cm, -half), (self.front_cm, -half)]


@dataclass(frozen=True)
class RobotSpec:
    """Everything the simulator needs to build one robot; `source` is the file it came from."""

    name: str
    wheel_diameter_mm: float
    axle_track_mm: float
    body: BodySpec
    motors: tuple[MotorSpec, ...]
    sensors: tuple[SensorSpec, ...]
    color: tuple[int, int, int] = DEFAULT_ROBOT_COLOR
    source: str | None = None

    def motor(self, port: str) -> MotorSpec | None:
        """The motor on `port` ('outB' or 'B'), or None."""
        wanted = normalise_port(port, MOTOR_PORTS)
        return next((m for m in self.motors if m.port == wanted), None)

    def sensor(self, port: str) -> SensorSpec | None:
        """The sensor on `port` ('in3' or '3'), or None."""
        wanted = normalise_port(port, SENSOR_PORTS)
        return next((s for s in self.sensors if s.port == wanted), None)

    @property
    def left_wheel(self) -> MotorSpec:
        """The motor that drives the left wheel."""
        return next(m for m in self.motors if m.wheel == "left")

    @property
    def right_wheel(self) -> MotorSpec:
        """The motor that drives the right wheel."""
        return next(m for m in self.motors if m.wheel == "right")

    @property
    def wheel_radius_cm(self) -> float:
        return self.wheel_diameter_mm / 20.0

    @property
    def axle_track_cm(self) -> float:
        """Distance between the two wheels' contact points."""
        return self.axle_track_mm / 10.0


# -- ports ------------------------------------------------------------------------


def normalise_port(text: str | int, ports: tuple[str, ...]) -> str | None:
    """'B', 'outB', 'ev3-ports:outB' -> 'outB'; '3', 'in3' -> 'in3'; None if not one of `ports`."""
    word = str(text).strip()
    if word.lower().startswith("ev3-ports:"):
        word = word[len("ev3-ports:") :]
    match = re.fullmatch(r"(out)?([a-dA-D])|(in)?([1-4])", word, flags=re.IGNORECASE)
    if match is None:
        return None
    port = f"out{match.group(2).upper()}" if match.group(2) else f"in{match.group(4)}"
    return port if port in ports else None


# -- reading ------------------------------------------------------------------------

_ROBOT_KEYS = ("name", "wheel_diameter_mm", "axle_track_mm", "body", "color", "motors", "sensors")
_SENSOR_KEYS = ("port", "kind", "angle_deg", "radius_cm", "facing", "aim_deg", "noise")


def load_robot(path: str | Path) -> RobotSpec:
    """Read a robot file."""
    return parse_robot(read_text_file(path, ROBOT_FILE), str(path))


def parse_robot(text: str, path: str = "<string>") -> RobotSpec:
    """Read a robot description from YAML text (a robot file's, or the live page's robot editor's), held to
    the robot file's limits (file_limits.py)."""
    node = load_yaml_text(text, path, ROBOT_FILE)
    if not node.is_mapping:
        raise node.error(f"a robot file is a mapping of keys like `name: My robot`, got {node.describe()}")
    return robot_from_mapping(node, source=path)


def robot_mapping_text(data: object, path: str = "<string>") -> str:
    """A robot file's mapping as plain data (the live page's robot editor sends it as JSON) written as a
    robot file's YAML, for parse_robot.  The data is held to the robot file's limits first, walked without
    recursion, so a deeply nested or huge request is a WorldFileError, not a RecursionError or a dump of
    megabytes."""
    limits = ROBOT_FILE
    nodes = chars = 0
    pending = [(data, 1)]
    while pending:
        value, depth = pending.pop()
        nodes += 1
        if depth > limits.depth or nodes > limits.nodes:
            raise WorldFileError(
                path,
                None,
                None,
                f"the robot is nested more than {limits.depth} deep or holds more than {limits.nodes:,} values; "
                "a robot file is a mapping of a few keys (docs/world-files.md)",
            )
        if isinstance(value, dict):
            pending += [(key, depth + 1) for key in value] + [(item, depth + 1) for item in value.values()]
        elif isinstance(value, (list, tuple)):
            pending += [(item, depth + 1) for item in value]
        elif isinstance(value, str):
            chars += len(value)
            if chars > limits.chars:
                raise WorldFileError(
                    path,
                    None,
                    None,
                    f"the robot's text is more than {limits.chars:,} characters (a robot file's limit)",
                )
        elif value is not None and not isinstance(value, (bool, int, float)):
            raise WorldFileError(
                path, None, None, f"a robot holds text, numbers, lists and mappings, not {value!r}"
            )
    import yaml

    return yaml.safe_dump(data, sort_keys=False, default_flow_style=None, allow_unicode=True)


def robot_from_mapping(node: Node, source: str | None = None, default_name: str = "robot") -> RobotSpec:
    """A robot from a YAML mapping (a robot file, or the inline `robot:` of a maze file)."""
    fields = node.as_fields("robot", _ROBOT_KEYS)
    name = fields.text("name", default=default_name)
    if len(name) > MAX_NAME_CHARS:
        raise fields.get("name").error(
            f"'name' is {len(name):,} characters long; a robot's name is at most {MAX_NAME_CHARS}; shorten it"
        )
    wheel_diameter = _ranged(
        fields,
        "wheel_diameter_mm",
        "mm",
        WHEEL_DIAMETER_MM,
        "wheel_diameter_mm: 56",
        "LEGO tyres are about 24 to 107 mm across; the EV3 set's is 56 mm",
    )
    axle_track = _ranged(
        fields,
        "axle_track_mm",
        "mm",
        AXLE_TRACK_MM,
        "axle_track_mm: 120",
        "two EV3 motors side by side put the wheels at least about 6 cm apart; the EV3 driving base's are "
        "120 mm apart",
    )
    body = _body(fields.require("body", "body: {front_cm: 9, back_cm: 7, width_cm: 15}"))
    color = _rgb(fields.get("color")) if "color" in fields else DEFAULT_ROBOT_COLOR
    motors_node = fields.require(
        "motors", "motors: [{port: B, kind: large, wheel: left}, {port: C, kind: large, wheel: right}]"
    )
    motor_items = motors_node.as_list("motors", "motors: [{port: B, kind: large, wheel: left}]")
    _check_count(motors_node, motor_items, MAX_MOTORS, "motors", "output ports A, B, C and D")
    motors = [_motor(item) for item in motor_items]
    sensors_node = fields.get("sensors")
    sensor_items = (
        sensors_node.as_list("sensors", "sensors: [{port: 3, kind: color}]") if sensors_node else []
    )
    if sensors_node is not None:
        _check_count(sensors_node, sensor_items, MAX_SENSORS, "sensors", "input ports 1, 2, 3 and 4")
    reach = _sensor_reach(body)
    sensors = [_sensor(item, reach) for item in sensor_items]
    _check_one_device_per_port(motors_node, motors, sensor_items, sensors)
    _check_wheels(motors_node, motors)
    return RobotSpec(
        name=name,
        wheel_diameter_mm=wheel_diameter,
        axle_track_mm=axle_track,
        body=body,
        motors=tuple(spec for spec, _ in motors),
        sensors=tuple(sensors),
        color=color,
        source=source,
    )


def _ranged(
    fields: Fields,
    name: str,
    unit: str,
    bounds: tuple[float, float],
    example: str,
    why: str,
    default: Any = None,
) -> float:
    """A number under `name` within `bounds` (file_limits.py), else an error giving the range and why."""
    if default is None:
        value = fields.number(name, unit=unit, example=example)
    else:
        value = fields.number(name, default=default, unit=unit, example=example)
    if not within(value, bounds):
        low, high = bounds
        raise fields.get(name).error(
            f"'{name}' must be {low:g} to {high:g} {unit}, got {value:g} ({why}); write e.g. `{example}`"
        )
    return value


def _check_count(node: Node, items: list[Node], limit: int, name: str, ports: str) -> None:
    if len(items) > limit:
        raise node.error(f"'{name}' lists {len(items):,}; the EV3 has {limit}, on its {ports}")


_BODY_WHY = "robots in leagues fit within 25 to 50 cm a side"


def _body(node: Node) -> BodySpec:
    fields = node.as_fields(
        "body", ("front_cm", "back_cm", "width_cm"), "body: {front_cm: 9, back_cm: 7, width_cm: 15}"
    )
    reach = (-BODY_REACH_CM, BODY_REACH_CM)
    front = _ranged(fields, "front_cm", "cm", reach, "front_cm: 9", _BODY_WHY)
    back = _ranged(fields, "back_cm", "cm", reach, "back_cm: 7", _BODY_WHY)
    width = _ranged(fields, "width_cm", "cm", (BODY_MIN_CM, BODY_REACH_CM), "width_cm: 15", _BODY_WHY)
    if front + back < BODY_MIN_CM:
        raise node.error(
            f"the body needs a length: front_cm + back_cm must be at least {BODY_MIN_CM:g} cm, "
            f"got {front + back:g}"
        )
    return BodySpec(front, back, width)


def _sensor_reach(body: BodySpec) -> float:
    """How far from the centre a sensor may sit: the body's farthest corner and a boom's length past it."""
    return max(math.hypot(x, y) for x, y in body.corners_cm()) + SENSOR_REACH_PAST_BODY_CM


def _rgb(node: Node) -> tuple[int, int, int]:
    help_text = "a colour name, '#rrggbb' or [red, green, blue] with 0..255 each"
    if node.is_sequence:
        values = node.as_numbers("color", 3, example="color: [230, 170, 30]")
        if all(0 <= v <= 255 for v in values):
            return (round(values[0]), round(values[1]), round(values[2]))
    elif node.is_scalar and not node.is_null:
        word = node.text.strip().lower()
        if word in EV3_COLORS:
            return EV3_COLORS[word].display_rgb
        if re.fullmatch(r"#[0-9a-f]{6}", word):
            return (int(word[1:3], 16), int(word[3:5], 16), int(word[5:7], 16))
    raise node.error(f"'color' must be {help_text}, got {node.describe()}")


def _port(node: Node, ports: tuple[str, ...], device: str) -> str:
    if not node.is_scalar or node.is_null:
        raise node.error(f"'port' must be a port name such as {ports[0]}, got {node.describe()}")
    port = normalise_port(node.text, ports)
    if port is not None:
        return port
    short = "A..D" if ports == MOTOR_PORTS else "1..4"
    other = SENSOR_PORTS if ports == MOTOR_PORTS else MOTOR_PORTS
    if normalise_port(node.text, other) is not None:
        plug = "output" if ports == MOTOR_PORTS else "input"
        return_hint = f"{device}s plug into {plug} ports"
    else:
        return_hint = "the EV3 has no such port"
    raise node.error(
        f"unknown {device} port {node.describe()}: {return_hint}; write one of {', '.join(ports)} (or just {short})"
    )


def _choice(fields: Fields, name: str, choices: tuple[str, ...], default: Any = None) -> str:
    node = fields.get(name)
    if node is None:
        if default is None:
            fields.require(name, f"{name}: {choices[0]}")
        return default
    word = node.as_text(name, f"{name}: {choices[0]}").strip().lower()
    if word not in choices:
        close = difflib.get_close_matches(word, choices, n=1)
        hint = f"did you mean '{close[0]}'? " if close else ""
        raise node.error(f"unknown {name} {node.describe()}; {hint}write one of {', '.join(choices)}")
    return word


_LIMITS_EXAMPLE = "limits_deg: [-90, 0]"
_LOAD_EXAMPLE = "load_pct: 30"


def _motor(node: Node) -> tuple[MotorSpec, Node]:
    fields = node.as_fields(
        "motor",
        ("port", "kind", "wheel", "mounted", "limits_deg", "load_pct"),
        "- {port: B, kind: large, wheel: left}",
    )
    port = _port(fields.require("port", "port: B"), MOTOR_PORTS, "motor")
    kind = _choice(fields, "kind", _sensor_classes().MOTORS, default="large")
    wheel_node = fields.get("wheel")
    wheel = None
    if wheel_node is not None and not wheel_node.is_null and wheel_node.text.strip().lower() != "none":
        wheel = _choice(fields, "wheel", WHEELS)
    mounted = _choice(fields, "mounted", MOUNTINGS, default="normal")
    for name in ("limits_deg", "load_pct"):
        if name in fields and wheel is not None:
            raise fields.key(name).error(
                f"'{name}' is for a motor that drives no wheel (an arm, a gripper, a launcher); a wheel motor's "
                f"shaft turns as the robot moves; remove `{name}` or `wheel: {wheel}`"
            )
    limits = _limits(fields.get("limits_deg")) if "limits_deg" in fields else None
    if limits is not None and not (-LIMITS_DEG <= limits[0] and limits[1] <= LIMITS_DEG):
        raise fields.get("limits_deg").error(
            f"'limits_deg' must lie within -{LIMITS_DEG:g} to {LIMITS_DEG:g} degrees (100 turns either way: "
            f"a winch; an arm turns less than one), got [{limits[0]:g}, {limits[1]:g}]; write e.g. "
            f"`{_LIMITS_EXAMPLE}`"
        )
    load = fields.number("load_pct", default=0.0, unit="% of the motor's stall torque", example=_LOAD_EXAMPLE)
    if not 0 <= load <= 100:
        raise fields.get("load_pct").error(
            f"'load_pct' is the torque of the load on the shaft in % of the motor's stall torque, from 0 (none) "
            f"to 100 (the motor stalls even at full power), got {load:g}; write e.g. `{_LOAD_EXAMPLE}`"
        )
    return MotorSpec(port, kind, wheel, mounted == "reversed", limits, load), node


def _limits(node: Node) -> tuple[float, float]:
    """A motor's end stops: [low, high] degrees from where its shaft starts, low <= 0 <= high."""
    low, high = node.as_numbers("limits_deg", 2, "degrees", _LIMITS_EXAMPLE)
    if not low < high:
        raise node.error(
            f"'limits_deg' is [low, high] with low below high (degrees the shaft can turn from where it starts), "
            f"got [{low:g}, {high:g}]; write e.g. `{_LIMITS_EXAMPLE}`"
        )
    if not low <= 0 <= high:
        raise node.error(
            f"the shaft starts at 0 degrees, which must lie within its limits [{low:g}, {high:g}] (the arm starts "
            f"between its end stops); write e.g. `limits_deg: [{min(low, 0):g}, {max(high, 0):g}]`"
        )
    return (low, high)


def _sensor(node: Node, reach: float) -> SensorSpec:
    fields = node.as_fields("sensor", None, "- {port: 3, kind: color, angle_deg: 0, radius_cm: 7}")
    port = _port(fields.require("port", "port: 3"), SENSOR_PORTS, "sensor")
    registry = _sensor_classes()
    kind = _choice(fields, "kind", registry.sensor_kinds())
    try:
        device = registry.sensor_class(kind)
    except (
        registry.DeviceKindError
    ) as error:  # a plug-in that does not load: name it at the robot file's line
        raise fields.get("kind").error(str(error)) from None
    option_table = device.OPTIONS
    fields.check_keys(_SENSOR_KEYS + tuple(option_table))
    facing = _choice(fields, "facing", FACINGS, default=device.FACINGS[0])
    if facing not in device.FACINGS:
        hint = device.FACING_HINTS.get(facing) or (
            f"a {kind} sensor cannot face {facing} in ev3sim2d (its device, {device.__name__}, measures "
            f"only facing {' or '.join(device.FACINGS)}); write `facing: {device.FACINGS[0]}`"
        )
        raise fields.get("facing").error(hint)
    turn = "one turn either way; 0 = straight ahead, 90 = to the left"
    angle = _ranged(fields, "angle_deg", "degrees", ANGLE_DEG, "angle_deg: 0", turn, default=0.0)
    radius = fields.number("radius_cm", default=0.0, unit="cm", example="radius_cm: 7")
    if radius < 0:
        raise fields.get("radius_cm").error(
            "'radius_cm' is a distance from the robot centre and cannot be negative"
        )
    if radius > reach:
        raise fields.get("radius_cm").error(
            f"'radius_cm' must be 0 to {reach:.4g} cm, got {radius:g}: a sensor sits on the robot, at most "
            f"{SENSOR_REACH_PAST_BODY_CM:g} cm past its body's farthest corner (a boom); move it closer or make "
            "the body bigger"
        )
    aim = _ranged(fields, "aim_deg", "degrees", ANGLE_DEG, "aim_deg: 90", turn, default=0.0)
    if "aim_deg" in fields and facing != "forward":
        raise fields.key("aim_deg").error(
            "'aim_deg' turns a sensor that faces forward; remove it or write `facing: forward`"
        )
    noise = fields.number("noise", default=0.0, example="noise: 0.5")
    if noise < 0:
        raise fields.get("noise").error(
            "'noise' is a standard deviation and cannot be negative; 0 turns noise off"
        )
    if not within(noise, NOISE):
        raise fields.get("noise").error(
            f"'noise' must be {NOISE[0]:g} to {NOISE[1]:g}, got {noise:g} (a standard deviation in the sensor's "
            "own unit: 100 is a colour or infrared reading's whole scale); write e.g. `noise: 0.5`"
        )
    options: dict[str, float] = {}
    for option, (default, unit, meaning) in option_table.items():
        value = fields.number(option, default=default, unit=unit, example=f"{option}: {default:g}")
        if value <= 0:
            raise fields.get(option).error(f"'{option}' must be more than 0 {unit}")
        low, high = sensor_option_range(option, unit)
        if not low <= value <= high and option in fields:
            raise fields.get(option).error(
                f"'{option}' ({meaning}) must be {low:g} to {high:g} {unit}, got {value:g}; "
                f"write e.g. `{option}: {default:g}`"
            )
        options[option] = value
    return SensorSpec(port, kind, angle, radius, facing, noise, options, aim)


def _check_one_device_per_port(
    motors_node: Node,
    motors: list[tuple[MotorSpec, Node]],
    sensor_items: list[Node],
    sensors: list[SensorSpec],
) -> None:
    seen: dict[str, Node] = {}
    pairs = [(spec.port, item) for spec, item in motors] + [
        (spec.port, item) for spec, item in zip(sensors, sensor_items, strict=True)
    ]
    for port, item in pairs:
        if port in seen:
            raise item.error(
                f"port {port} already has a device (line {seen[port].line}); each port takes one motor or sensor"
            )
        seen[port] = item


def _check_wheels(motors_node: Node, motors: list[tuple[MotorSpec, Node]]) -> None:
    for side, example in (
        ("left", "- {port: B, kind: large, wheel: left}"),
        ("right", "- {port: C, kind: large, wheel: right}"),
    ):
        drivers = [item for spec, item in motors if spec.wheel == side]
        if not drivers:
            raise motors_node.error(
                f"no motor drives the {side} wheel; add `wheel: {side}` to a motor, e.g. `{example}`"
            )
        if len(drivers) > 1:
            raise drivers[1].error(
                f"two motors drive the {side} wheel (the first on line {drivers[0].line}); a robot has one {side} wheel motor"
            )


# -- writing ------------------------------------------------------------------------


def _number(value: float) -> str:
    value = float(value)
    return str(int(value)) if value.is_integer() else repr(value)


def robot_yaml(spec: RobotSpec) -> str:
    """The robot as a robot file's text, in the shipped files' layout; parse_robot reads it back equal
    (its comments are not kept: a RobotSpec has none)."""
    body = spec.body
    lines = [
        "# a robot file (docs/world-files.md); written by ev3sim2d",
        f"name: {_quoted(spec.name)}",
        f"wheel_diameter_mm: {_number(spec.wheel_diameter_mm)}",
        f"axle_track_mm: {_number(spec.axle_track_mm)}",
        "body:",
        f"  front_cm: {_number(body.front_cm)}",
        f"  back_cm: {_number(body.back_cm)}",
        f"  width_cm: {_number(body.width_cm)}",
        f"color: [{', '.join(str(c) for c in spec.color)}]",
        "",
        "motors:",
    ]
    for motor in spec.motors:
        parts = [f"port: {motor.port[3:]}", f"kind: {motor.kind}"]
        if motor.wheel:
            parts.append(f"wheel: {motor.wheel}")
        if motor.reversed:
            parts.append("mounted: reversed")
        if motor.limits_deg is not None:
            parts.append(f"limits_deg: [{_number(motor.limits_deg[0])}, {_number(motor.limits_deg[1])}]")
        if motor.load_pct:
            parts.append(f"load_pct: {_number(motor.load_pct)}")
        lines.append(f"  - {{{', '.join(parts)}}}")
    lines += ["", "sensors:" if spec.sensors else "sensors: []"]
    for sensor in spec.sensors:
        parts = [
            f"port: {sensor.port[2:]}",
            f"kind: {sensor.kind}",
            f"angle_deg: {_number(sensor.angle_deg)}",
            f"radius_cm: {_number(sensor.radius_cm)}",
            f"facing: {sensor.facing}",
        ]
        if sensor.facing == "forward" and sensor.aim_deg:
            parts.append(f"aim_deg: {_number(sensor.aim_deg)}")
        if sensor.noise:
            parts.append(f"noise: {_number(sensor.noise)}")
        parts += [f"{name}: {_number(value)}" for name, value in sensor.options.items()]
        lines.append(f"  - {{{', '.join(parts)}}}")
    return "\n".join(lines) + "\n"


def _quoted(text: str) -> str:
    import json

    return json.dumps(text, ensure_ascii=False)  # a JSON string is a YAML string


# -- shipped robots ---------------------------------------------------------------------


def shipped_robots_dir() -> Path:
    """The folder of robot files that come with ev3sim2d."""
    return Path(__file__).resolve().parents[1] / "robots"


DEFAULT_ROBOT_FILE = "ev3-driving-base.yaml"


@functools.lru_cache(maxsize=1)
def _default_robot() -> RobotSpec:
    return load_robot(shipped_robots_dir() / DEFAULT_ROBOT_FILE)


def default_robot() -> RobotSpec:
    """The EV3 Education driving base (read once; each call gets its own copy)."""
    return copy.deepcopy(_default_robot())


def find_robot(name_or_path: str | Path, base_dir: Path | None = None) -> Path | None:
    """A robot file: a path (relative to `base_dir` first), else a shipped robot by name; None if neither.

    A path written in a file comes here through `written_path`, so `robots\\bot.yaml` is found on any system.
    """
    candidate = Path(name_or_path)
    places = [base_dir / candidate] if base_dir is not None and not candidate.is_absolute() else []
    places.append(candidate)
    stem = candidate.name if candidate.suffix in (".yaml", ".yml") else candidate.name + ".yaml"
    places.append(shipped_robots_dir() / stem)
    return next((place for place in places if place.is_file()), None)


def shipped_robot_names() -> list[str]:
    """Names of the robot files that come with ev3sim2d."""
    return sorted(p.stem for p in shipped_robots_dir().glob("*.yaml"))
