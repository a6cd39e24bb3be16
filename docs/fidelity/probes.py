"""The checks behind docs/fidelity.md: each documented motor attribute, command, stop action and state,
and each sensor mode, tried on ev3sim2d's simulated devices, one `Row` each.

A robot stands in a small walled arena (`Bench`), stepped tick by tick in-process; a probe reads and
writes its devices' sysfs attributes as a program on the brick does (errors are the OSErrors a
brick's files give).  Large and Medium motors are probed on motors that drive no wheel; `stalled` and
`overloaded` on the wheels of a robot pushing a wall.  A sensor mode is compared field by field with
the driver's table, read in the arena, and swept across its documented range: value0 must read what
the device measured, and bin_data must hold what the driver turns into that value.

What a check claims is in the row's cells (fixed text); what it measured only in its failures, so the
page changes when the devices' behaviour against the drivers changes, not when a reading does.
"""

from __future__ import annotations

import errno
import re
import struct
from collections.abc import Callable
from dataclasses import dataclass, field

from ev3sim2d.devices.motor import KINDS as MOTOR_KINDS
from ev3sim2d.devices.registry import BUILT_IN
from ev3sim2d.simulator.simulation import TICK_US, Simulation
from ev3sim2d.world.maze_file import parse_maze
from ev3sim2d.world.pose import Pose
from ev3sim2d.world.robot_spec import parse_robot

STRUCT = {"u8": "<B", "s8": "<b", "u16": "<H", "s16": "<h", "s16_be": ">h", "s32": "<i", "s32be": ">i"}
STRUCT["float"] = "<f"
ERRNO = {errno.EINVAL: "EINVAL", errno.EACCES: "EACCES", errno.ENOENT: "ENOENT", errno.ENXIO: "ENXIO"}
ERRNO[errno.EBUSY] = "EBUSY"
# lego-sensor attributes no simulated sensor has: one difference entry says why for all of them
SENSOR_ATTRIBUTES_NOT_SIMULATED = {"poll_ms", "fw_version", "text_value", "direct"}


def slug(text: str) -> str:
    """A difference's key (and the page's anchor for it) from words: lower case, hyphens."""
    return re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-")


@dataclass
class Row:
    """One line of a table: what the driver documents, what was checked, and what did not hold."""

    id: str  # "lego-ev3-ir:IR-SEEK", "tacho-motor:speed_sp", "command:run-forever", ...
    cells: list[str]
    failures: list[tuple[str, str]] = field(default_factory=list)  # (difference key, what failed)
    caveats: list[tuple[str, str]] = field(default_factory=list)  # (difference key, what differs)

    @property
    def ok(self) -> bool:
        return not self.failures

    def keys(self) -> list[str]:
        """The differences the row links to, failures first."""
        return list(dict.fromkeys(key for key, _ in self.failures + self.caveats))


class Checks:
    """A row's checks as they run: a documented behaviour not met is a failure (the row is ✗); one that
    only the drivers' code states is a caveat (the row stays ✓)."""

    def __init__(self, key: str) -> None:
        self.key = key  # the difference a failure files under unless it names its own
        self.failures: list[tuple[str, str]] = []
        self.caveats: list[tuple[str, str]] = []

    def expect(self, ok: bool, what: str, key: str | None = None) -> bool:
        if not ok:
            self.failures.append((key or self.key, what))
        return ok

    def detail(self, ok: bool, key: str, what: str) -> bool:
        if not ok:
            self.caveats.append((key, what))
        return ok

    def run(self, what: str, probe: Callable[..., object], *args) -> None:
        """Run probe(*args); an exception from a device is a failure of the row, not a crash of the page."""
        try:
            probe(*args)
        except Exception as error:  # noqa: BLE001 - whatever it is, the row says it
            self.expect(False, f"{what}: {type(error).__name__}: {error}")

    def row(self, row_id: str, cells: list[str]) -> Row:
        return Row(row_id, cells, self.failures, self.caveats)


def error_of(action: Callable[[], object]) -> int | None:
    """The errno an attribute access fails with; None when it succeeds."""
    try:
        action()
    except OSError as error:
        return error.errno
    return None


def errno_name(number: int | None) -> str:
    return "no error" if number is None else ERRNO.get(number, str(number))


# ------------------------------------------------------------------------------------ the bench
ARENA_CELLS = 20  # 20 x 20 cells of 12 cm, walled: the right wall's face is at x = 228 cm
WALL_X = (ARENA_CELLS - 1) * 12
ROBOT = """name: fidelity probe
wheel_diameter_mm: 56
axle_track_mm: 120
body: {front_cm: 9, back_cm: 7, width_cm: 15}
motors:
  - {port: A, kind: medium}
  - {port: B, kind: large, wheel: left}
  - {port: C, kind: large, wheel: right}
  - {port: D, kind: large}
"""
FREE_MOTOR = {"medium": "outA", "large": "outD"}  # a motor of each kind that drives no wheel
AT_WALL_X = WALL_X - 9.2  # the robot's front (and a touch sensor's bumper) 0.2 cm from the wall
OPEN_X = 160.0  # a wall 59 cm ahead of the robot's front


def _arena() -> str:
    rows = ["#" * ARENA_CELLS] + ["#" + "." * (ARENA_CELLS - 2) + "#"] * (ARENA_CELLS - 2)
    rows.append("#" * ARENA_CELLS)
    grid = "\n".join("  " + row for row in rows)
    return f"title: fidelity probe\ncell_cm: 12\ngrid: |\n{grid}\nstart:\n  x_cm: 60\n  y_cm: 120\n"


class Bench:
    """A robot in the arena, facing the right wall, its devices read and written as a program would."""

    def __init__(self, x_cm: float = 100.0, sensor: str = "", states: list[str] | None = None) -> None:
        world = parse_maze(_arena(), "<fidelity arena>", robots=False)
        spec = parse_robot(ROBOT + (f"sensors:\n  - {sensor}\n" if sensor else "sensors: []\n"))
        self.sim = Simulation(world, [("probe", spec, Pose(x_cm, 120.0, 0.0))])
        self.robot = self.sim.robots[0]
        self.now_us = 0
        self.states = states if states is not None else []  # every motor state read

    def tick(self, count: int = 1) -> None:
        for _ in range(count):
            self.now_us += TICK_US
            self.sim.tick(self.now_us)

    def motor(self, port: str):
        return self.robot.motors[port]

    def read(self, device, attribute: str) -> str:
        value = device.read(attribute)
        if attribute == "state":
            self.states.append(value)
        return value

    def number(self, device, attribute: str) -> int:
        return int(self.read(device, attribute))

    def speeds(self, motor, ticks: int) -> list[int]:
        """The speed read after each of the next `ticks` ticks."""
        found = []
        for _ in range(ticks):
            self.tick()
            found.append(self.number(motor, "speed"))
        return found


def near(value: float, target: float, tolerance: float) -> bool:
    return abs(value - target) <= tolerance


# ------------------------------------------------------------------------------------ sensors
def sensor_entry(cls) -> str:
    """The robot-file entry of a sensor of this class on port 1, at the robot's front."""
    return f"{{port: 1, kind: {cls.KIND}, angle_deg: 0, radius_cm: 9, facing: {cls.FACINGS[0]}}}"


SCENE_X = {"touch": AT_WALL_X}  # where a kind is read (others: OPEN_X); the touch sensor is pressed there
TURNING = {"gyro"}  # kinds read while the robot turns, so that they read something


def driver_value(mode: dict, raw: int, facts: dict) -> int | None:
    """value<N> as the driver computes it from the raw reading bin_data holds (lego_sensor_default_scale,
    or the mode's own scale function); None for a scale function these checks do not know."""
    if mode["scale"] == "lego_ev3_touch_sensor_scale":
        return 1 if raw > facts["touch_threshold_mv"]["value"] else 0
    if mode["scale"]:
        return None
    raw_min, raw_max, si_min, si_max = (mode[k] for k in ("raw_min", "raw_max", "si_min", "si_max"))
    if raw_min == si_min and raw_max == si_max:
        return raw
    top, bottom = (raw - raw_min) * (si_max - si_min), raw_max - raw_min
    quotient = abs(top) // abs(bottom)  # C's integer division, toward zero
    return (quotient if (top >= 0) == (bottom > 0) else -quotient) + si_min


def documented_range(mode: dict) -> tuple[int, int] | None:
    """The lowest and highest value the mode's @valueN lines document; None if one documents none."""
    ranges = [v["range"] for v in mode["values"]]
    if not ranges or any(r is None for r in ranges):
        return None
    return min(r[0] for r in ranges), max(r[1] for r in ranges)


def decode(data: str, data_format: str, count: int) -> list:
    code = STRUCT[data_format]
    size = struct.calcsize(code)
    raw = data.encode("latin-1")
    return [struct.unpack(code, raw[i * size : (i + 1) * size])[0] for i in range(count)]


def sweep_points(low: int, high: int) -> list[int]:
    """Values across [low, high]: every one when there are few, else about 400 with both ends."""
    if high - low <= 2000:
        return list(range(low, high + 1))
    step = (high - low) / 400
    return sorted({low, high, *(round(low + i * step) for i in range(401))})


def mode_row(cls, driver: dict, mode: dict, data: dict, bench: Bench) -> Row:
    """A sensor mode: our Mode against the driver's table, then read through the simulated device."""
    name = mode["name"]
    checks = Checks(slug(f"{driver['driver']} {name}"))
    bin_data_key = slug(f"{driver['driver']} bin_data")
    ours = cls.MODES.get(name)
    documented = documented_range(mode)
    if ours is None:
        checks.expect(False, f"{cls.__name__} has no mode {name}")
    else:
        order = list(cls.MODES).index(name)
        checks.expect(order == mode["index"], f"it is mode {order} here, {mode['index']} in the driver")
        for what, theirs, mine in (
            ("num_values", mode["num_values"], ours.num_values),
            ("decimals", mode["decimals"], ours.decimals),
            ("units", mode["units"], ours.units),
            ("bin_data_format", mode["bin_data_format"], ours.data_format),
        ):
            checks.expect(theirs == mine, f"{what} is {mine!r} here, {theirs!r} in the driver")
        if documented is not None:
            checks.expect(
                (ours.low, ours.high) == documented,
                f"values are kept within {ours.low:g}…{ours.high:g} here, documented "
                f"{documented[0]}…{documented[1]}",
            )
        scaled = (mode["raw_min"], mode["raw_max"]) != (mode["si_min"], mode["si_max"])
        if mode["scale"]:
            checks.expect(
                ours.raw is not None,
                f"bin_data holds value0 itself here; the driver's holds the raw reading "
                f"{mode['scale']} turns into value0",
                bin_data_key,
            )
        elif scaled:
            raw = (mode["raw_min"], mode["raw_max"], mode["si_min"], mode["si_max"])
            checks.expect(ours.raw == raw, f"bin_data's scaling is {ours.raw} here, {raw} in the driver")
        else:
            checks.expect(ours.raw is None, f"bin_data is scaled by {ours.raw} here; the driver's is not")
        span = documented or (int(ours.low), int(ours.high))
        read_mode(checks, bench, mode, span, data["facts"], bin_data_key)
    for other in data["other_refs"]:
        changed = other["modes"].get(driver["driver"], {}).get(name)
        if changed:
            text = ", ".join(f"{k} {v}" for k, v in changed.items())
            checks.caveats.append(
                (slug(f"{other['ref']} {driver['driver']}"), f"{other['ref']}, {name}: {text}")
            )
    shown_range = "—" if documented is None else f"{documented[0]}…{documented[1]}"
    cells = [
        f"`{name}`",
        str(mode["index"]),
        str(mode["num_values"]),
        str(mode["decimals"]),
        f"`{mode['units']}`" if mode["units"] else "",
        f"`{mode['bin_data_format']}`",
        shown_range,
    ]
    return checks.row(f"{driver['driver']}:{name}", cells)


def read_mode(checks: Checks, bench: Bench, mode: dict, span: tuple[int, int], facts: dict, key: str) -> None:
    """Select the mode and read it as a program does; then sweep its values."""
    sensor = bench.robot.sensors["in1"]
    name, count, data_format = mode["name"], mode["num_values"], mode["bin_data_format"]

    def attributes() -> None:
        sensor.write("mode", name)
        bench.tick()
        checks.expect(sensor.read("mode") == name, f"mode reads {sensor.read('mode')!r} after writing {name}")
        for attribute in ("num_values", "decimals", "units", "bin_data_format"):
            value = sensor.read(attribute)
            checks.expect(value == str(mode[attribute]), f"{attribute} reads {value!r}")
        values = [int(sensor.read(f"value{n}")) for n in range(count)]
        if count < 8:
            failed = error_of(lambda: sensor.read(f"value{count}"))
            checks.expect(failed == errno.ENXIO, f"value{count} (past num_values) gives {errno_name(failed)}")
        data = sensor.read("bin_data")
        size = struct.calcsize(STRUCT[data_format]) * count
        if checks.expect(len(data) >= size, f"bin_data holds {len(data)} bytes, {size} needed", key):
            decoded = [driver_value(mode, raw, facts) for raw in decode(data, data_format, count)]
            if None not in decoded:
                checks.expect(
                    decoded == values, f"bin_data {decoded} as the driver reads it, value<N> {values}", key
                )

    def sweep() -> None:
        """Each value across the range as the device would measure it: value0 reads it, and bin_data
        holds what the driver turns into it."""
        scale = 10 ** mode["decimals"]
        for value in sweep_points(*span):
            bench.robot.tick += 1  # (a new sample: the device measures again; nothing else moves)
            sensor.measure = lambda _mode, v=value: (v / scale,) * count
            sensor.write("mode", name)  # (a single-measurement mode measures when its mode is written)
            read = int(sensor.read("value0"))
            if not checks.expect(read == value, f"value0 reads {read} for a measured {value}"):
                return
            raw = decode(sensor.read("bin_data"), data_format, 1)[0]
            back = driver_value(mode, raw, facts)
            if back is not None and not checks.expect(
                back == value, f"bin_data holds {raw} for value0 {value}; the driver makes that {back}", key
            ):
                return

    checks.run(f"reading {name}", attributes)
    own = sensor.__dict__.get("measure")  # (a forward-facing colour sensor chose its own at start)
    checks.run(f"sweeping {name}", sweep)
    if own is None:
        sensor.__dict__.pop("measure", None)
    else:
        sensor.measure = own


SENSOR_ROW = "(the sensor: its driver_name, its modes in the driver's order, mode 0 first)"


def sensor_sections(data: dict) -> list[tuple[type, dict | None, list[Row]]]:
    """(class, the driver's sensor, rows) for each kind of sensor ev3sim2d has built in."""
    drivers = {s["driver"]: s for s in data["sensors"]}
    found = []
    for cls in BUILT_IN:
        driver = drivers.get(cls.DRIVER)
        checks = Checks(slug(f"{cls.DRIVER} modes"))
        if not checks.expect(driver is not None, "the drivers have no sensor of this name"):
            found.append((cls, None, [checks.row(f"{cls.DRIVER}:modes", [SENSOR_ROW] + [""] * 6)]))
            continue
        bench = Bench(SCENE_X.get(cls.KIND, OPEN_X), sensor_entry(cls))
        if cls.KIND in TURNING:
            for port, speed in (("outB", "300"), ("outC", "-300")):
                bench.motor(port).write("speed_sp", speed)
                bench.motor(port).write("command", "run-forever")
            bench.tick(20)
        sensor = bench.robot.sensors["in1"]
        documented = [m["name"] for m in driver["modes"]]
        extra = [m for m in cls.MODES if m not in documented]
        checks.expect(
            sensor.read("driver_name") == driver["driver"],
            f"driver_name reads {sensor.read('driver_name')!r}",
        )
        checks.expect(not extra, f"modes the driver does not have: {', '.join(extra)}")
        checks.expect(sensor.read("modes") == " ".join(documented), f"modes reads {sensor.read('modes')!r}")
        checks.expect(sensor.read("mode") == documented[0], f"it starts in {sensor.read('mode')}, not mode 0")
        rows = [checks.row(f"{driver['driver']}:modes", [SENSOR_ROW, "", "", "", "", "", ""])]
        rows += [mode_row(cls, driver, mode, data, bench) for mode in driver["modes"]]
        found.append((cls, driver, rows))
    return found


def sensor_class_rows(data: dict) -> list[Row]:
    """The lego-sensor class's attributes, each on every kind of sensor ev3sim2d has built in."""
    sensors = [
        (cls, Bench(SCENE_X.get(cls.KIND, OPEN_X), sensor_entry(cls)).robot.sensors["in1"])
        for cls in BUILT_IN
    ]
    rows = []
    for attribute in data["lego_sensor_class"]["attributes"]:
        name, access = attribute["name"], attribute["access"]
        checks = Checks(slug(f"lego-sensor {name}"))
        key = "sensor-attributes-not-simulated" if name in SENSOR_ATTRIBUTES_NOT_SIMULATED else None
        names = [f"value{n}" for n in range(8)] if name == "value<N>" else [name]
        for cls, sensor in sensors:
            for one in names:
                readable = error_of(lambda s=sensor, a=one: s.read(a))
                writable = error_of(lambda s=sensor, a=one: s.write(a, "\x11" if a == "direct" else ""))
                problems = []
                if "read" in access and readable in (errno.ENOENT, errno.EACCES):
                    problems.append(f"cannot be read ({errno_name(readable)})")
                if access == "read-only" and writable != errno.EACCES:
                    problems.append(f"a write gives {errno_name(writable)}, not EACCES")
                if "write" in access and writable in (errno.ENOENT, errno.EACCES):
                    problems.append(f"cannot be written ({errno_name(writable)})")
                if access == "write-only" and readable != errno.EACCES:
                    problems.append(f"a read gives {errno_name(readable)}, not EACCES")
                if problems:
                    checks.expect(False, f"{cls.KIND}: `{one}` " + ", ".join(problems), key)
        rows.append(
            checks.row(f"lego-sensor:{name}", [f"`{name}`", access, first_sentence(attribute["description"])])
        )
    return rows


# ------------------------------------------------------------------------------------- motors
def motor_kinds(data: dict) -> list[tuple[str, dict | None]]:
    """(kind, the driver's motor) for each kind of motor ev3sim2d simulates."""
    motors = {m["driver"]: m for m in data["motors"]}
    return [(kind, motors.get(driver_name)) for kind, (driver_name, _speed, _kp) in MOTOR_KINDS.items()]


class MotorProbe:
    """A free motor of one kind on a fresh bench, and the checks of the row it serves."""

    def __init__(self, kind: str, motor: dict, data: dict, checks: Checks, states: list[str]) -> None:
        self.kind, self.spec, self.data, self.checks = kind, motor, data, checks
        self.bench = Bench(states=states)
        self.port = FREE_MOTOR[kind]
        self.m = self.bench.motor(self.port)

    def read(self, attribute: str) -> str:
        return self.bench.read(self.m, attribute)

    def number(self, attribute: str) -> int:
        return self.bench.number(self.m, attribute)

    def write(self, attribute: str, value) -> None:
        self.m.write(attribute, str(value))

    def tick(self, count: int = 1) -> None:
        self.bench.tick(count)

    def expect(self, ok: bool, what: str) -> bool:
        return self.checks.expect(ok, f"{self.kind}: {what}")

    def refuses(self, attribute: str, value) -> None:
        failed = error_of(lambda: self.write(attribute, value))
        self.expect(
            failed == errno.EINVAL, f"writing {value} to {attribute} gives {errno_name(failed)}, not EINVAL"
        )

    def accepts(self, attribute: str, value) -> None:
        failed = error_of(lambda: self.write(attribute, value))
        if self.expect(failed is None, f"writing {value} to {attribute} gives {errno_name(failed)}"):
            self.expect(
                self.read(attribute) == str(value),
                f"{attribute} reads {self.read(attribute)!r} after {value}",
            )

    def starts_at(self, attribute: str, value) -> None:
        self.expect(
            self.read(attribute) == str(value),
            f"{attribute} reads {self.read(attribute)!r} at first, not {value}",
        )


def attribute_claim(name: str, tacho: dict, facts: dict) -> str:
    """What the probe of an attribute checks, in words (the same for every kind of motor)."""
    ramp = facts["ramp_sp_max"]["value"]
    claims = {
        "address": "the port, `ev3-ports:outA`…",
        "command": "(the commands below); another word: EINVAL",
        "commands": f"`{' '.join(tacho['commands']['names'])}`",
        "count_per_rot": "the driver's",
        "count_per_m": "absent (a rotation motor)",
        "full_travel_count": "absent (a rotation motor)",
        "driver_name": "the driver's name",
        "duty_cycle": "`duty_cycle_sp` in run-direct; -100…100 regulated",
        "duty_cycle_sp": "0 at first; -100…100, else EINVAL; a new one takes effect at once in run-direct",
        "polarity": (
            "`normal` at first; `normal`, `inversed`, else EINVAL; inversed wheels drive the robot backwards; "
            "inversing negates what position and the setpoints read, the shaft turning on as before"
        ),
        "position": (
            "counts what the shaft turned; written, reads back, also while the motor runs; "
            "written during a run to a position, ends it there"
        ),
        "max_speed": "the driver's",
        "position_sp": "0 at first; any 32-bit integer, else EINVAL",
        "speed": "the speed turned, in counts/s",
        "speed_sp": "0 at first; -max_speed…max_speed, else EINVAL",
        "ramp_up_sp": f"0 at first; 0…{ramp}, else EINVAL; 0 to half max_speed in half of it",
        "ramp_down_sp": f"0 at first; 0…{ramp}, else EINVAL; half max_speed to 0 in half of it",
        "state": "(the flags below); a write: EACCES",
        "stop_action": f"`coast` at first; `{' '.join(tacho['stop_actions']['names'])}`, else EINVAL",
        "stop_actions": f"`{' '.join(tacho['stop_actions']['names'])}`",
        "time_sp": "0 at first; negative: EINVAL",
    }
    if "_pid/" in name:
        return "the driver's default; written, reads back; negative: EINVAL"
    return claims.get(name, "")


def probe_attribute(name: str, probe: MotorProbe) -> None:
    tacho, facts, spec = probe.data["tacho_motor_class"], probe.data["facts"], probe.spec
    if name == "address":
        probe.starts_at(name, f"ev3-ports:{probe.port}")
    elif name == "driver_name":
        probe.starts_at(name, spec["driver"])
    elif name in ("commands", "stop_actions"):
        probe.starts_at(name, " ".join(tacho[name]["names"]))
    elif name in ("count_per_rot", "max_speed"):
        probe.starts_at(name, spec[name])
    elif name in ("count_per_m", "full_travel_count"):
        failed = error_of(lambda: probe.read(name))
        probe.expect(
            failed == errno.ENOENT, f"a rotation motor has {name}: reading gives {errno_name(failed)}"
        )
    elif "_pid/" in name:
        group, k = name.split("/")
        probe.starts_at(name, spec[group][k])
        probe.accepts(name, 1234)
        probe.refuses(name, -1)
    elif name == "duty_cycle_sp":
        probe.starts_at(name, 0)
        for value in (-100, 100):
            probe.accepts(name, value)
        for value in (101, -101):
            probe.refuses(name, value)
        probe.write(name, 50)
        probe.write("command", "run-direct")
        probe.tick(10)
        probe.write(name, -30)  # "changing duty_cycle_sp while running *will* take effect immediately"
        probe.tick()
        probe.expect(
            probe.number("speed") < 0,
            f"duty_cycle_sp -30 written while running: speed {probe.number('speed')}",
        )
    elif name == "speed_sp":
        probe.starts_at(name, 0)
        top = spec["max_speed"]
        for value in (top, -top):
            probe.accepts(name, value)
        for value in (top + 1, -top - 1):
            probe.refuses(name, value)
    elif name == "position_sp":
        probe.starts_at(name, 0)
        for value in (2**31 - 1, -(2**31)):
            probe.accepts(name, value)
        probe.refuses(name, 2**31)
    elif name == "time_sp":
        probe.starts_at(name, 0)
        probe.accepts(name, 60000)
        probe.refuses(name, -1)
    elif name in ("ramp_up_sp", "ramp_down_sp"):
        probe.starts_at(name, 0)
        top = facts["ramp_sp_max"]["value"]
        probe.accepts(name, top)
        for value in (top + 1, -1):
            probe.refuses(name, value)
        ramp_time(name, probe)
    elif name == "polarity":
        probe.starts_at(name, "normal")
        for value in tacho["polarities"]["names"]:
            probe.accepts(name, value)
        probe.refuses(name, "backwards")
        polarity(probe)
    elif name == "position":
        probe.write("speed_sp", 500)
        probe.write("command", "run-forever")
        probe.tick(100)
        turned = probe.number(name)
        probe.expect(near(turned, 500, 2), f"after 1 s at speed_sp 500 position reads {turned}")
        written_while_running(probe, facts)
        probe.write("stop_action", "hold")
        probe.write("command", "stop")
        probe.tick(10)
        for value in (100, -(2**31)):
            probe.accepts(name, value)
        probe.refuses(name, 2**31)
    elif name == "speed":
        probe.write("speed_sp", -700)
        probe.write("command", "run-forever")
        probe.tick(20)
        probe.expect(probe.number(name) == -700, f"at speed_sp -700 speed reads {probe.number(name)}")
    elif name == "duty_cycle":
        probe.write("duty_cycle_sp", -40)
        probe.write("command", "run-direct")
        probe.tick(5)
        probe.expect(probe.number(name) == -40, f"run-direct at duty_cycle_sp -40 reads {probe.number(name)}")
        probe.write("speed_sp", spec["max_speed"] // 2)
        probe.write("command", "run-forever")
        probe.tick(5)
        probe.expect(-100 <= probe.number(name) <= 100, f"a regulated run reads {probe.number(name)}")
    elif name == "state":
        failed = error_of(lambda: probe.write(name, "running"))
        probe.expect(failed == errno.EACCES, f"a write gives {errno_name(failed)}")
    elif name == "stop_action":
        probe.starts_at(name, "coast")
        for value in tacho["stop_actions"]["names"]:
            probe.accepts(name, value)
        probe.refuses(name, "float")
    elif name == "command":
        probe.refuses(name, "run-backwards")
    else:
        probe.expect(False, f"no probe for the attribute {name}")


def written_while_running(probe: MotorProbe, facts: dict) -> None:
    """The driver's code: legoev3_motor_set_position's EBUSY test is never true, so position is written
    while the motor runs too; and the written position becomes a run to a position's target, so that run
    ends where the shaft is (update_position)."""
    test, write = facts["position_busy_test"], facts["position_write_sets_target"]
    failed = error_of(lambda: probe.write("position", 0))
    probe.expect(
        failed is None,
        f"writing position while the motor runs gives {errno_name(failed)}; a brick accepts it "
        f"({test['file']}:{test['line']} `{test['source']}` masks with {test['value']}, which is 0)",
    )
    probe.tick(10)
    counted = probe.number("position")
    probe.expect(near(counted, 50, 2), f"written 0 at speed_sp 500, position reads {counted} 100 ms later")
    probe.write("stop_action", "hold")
    probe.write("position_sp", 720)
    probe.write("command", "run-to-abs-pos")
    probe.tick(20)
    probe.write("position", 0)
    probe.tick(5)
    position, state = probe.number("position"), probe.read("state")
    probe.expect(
        position == 0 and state == "holding",
        f"position 0 written 200 ms into a run-to-abs-pos to 720: {position}, {state!r} 50 ms later; on a "
        f"brick it ends there ({write['file']}:{write['line']} `{write['source']}`)",
    )


def ramp_time(name: str, probe: MotorProbe) -> None:
    """The speed changes by max_speed per ramp_*_sp ms: to half of max_speed takes half the setpoint."""
    half = probe.spec["max_speed"] // 2
    probe.write("command", "reset")
    probe.write(name, 1000)
    probe.write("speed_sp", half)
    probe.write("stop_action", "brake")  # (the ramp alone: a coast after it is not the ramp's)
    probe.write("command", "run-forever")
    if name == "ramp_down_sp":
        probe.tick(10)
        probe.write("command", "stop")
    speeds = probe.bench.speeds(probe.m, 70)
    target = half if name == "ramp_up_sp" else 0
    reached = next((10 * (i + 1) for i, s in enumerate(speeds) if s == target), None)
    probe.expect(
        reached is not None and near(reached, 500, 20),
        f"to {target} with {name} 1000 takes {reached} ms, not 500",
    )


def polarity(probe: MotorProbe) -> None:
    """Inversed, a positive speed turns the shaft the other way: both wheels inversed, the robot backs.
    The driver's code keeps the count and the setpoints in the motor's frame and negates what position
    and they read with the polarity (position_show and the others), so inversing it flips their sign
    and leaves the shaft turning as it did."""
    bench = Bench()
    for port in ("outB", "outC"):
        motor = bench.motor(port)
        motor.write("polarity", "inversed")
        motor.write("speed_sp", "300")
        motor.write("command", "run-forever")
    x0 = bench.robot.x
    bench.tick(50)
    probe.expect(
        bench.robot.x < x0 - 5,
        f"wheels inversed at speed_sp 300: the robot went {bench.robot.x - x0:+.1f} cm",
    )
    probe.write("polarity", "normal")  # (the checks of the values before left it inversed)
    probe.write("stop_action", "hold")
    probe.write("speed_sp", 360)
    probe.write("position_sp", 90)
    probe.write("command", "run-to-abs-pos")
    probe.tick(50)
    before = [probe.number(a) for a in ("position", "position_sp", "speed_sp")]
    probe.write("polarity", "inversed")
    after = [probe.number(a) for a in ("position", "position_sp", "speed_sp")]
    fact = probe.data["facts"]["position_follows_polarity"]
    probe.expect(
        after == [-value for value in before],
        f"position, position_sp, speed_sp read {before}, then {after} once polarity is inversed; on a brick "
        f"{[-value for value in before]} ({fact['file']}:{fact['line']} `{fact['source']}`)",
    )
    probe.write("command", "run-forever")
    probe.tick(10)
    position, speed = probe.number("position"), probe.number("speed")
    probe.expect(
        near(position, -126, 1) and speed == -360,
        f"run-forever at speed_sp 360 written before inversing: position {position}, speed {speed} 100 ms "
        "later; on a brick the shaft turns on as before, read negated (-126, -360)",
    )


COMMAND_CLAIMS = {
    "run-forever": "still running at speed_sp 500 after 2 s, position 1000",
    "run-to-abs-pos": "ends on position_sp 720 (speed_sp -500: the sign is ignored), then `holding`",
    "run-to-rel-pos": (
        "from 100 by position_sp -300: ends on -200, then `holding`; right after a run-to-rel-pos, "
        "counts from its target"
    ),
    "run-timed": "time_sp 1500 at 400: `running` at 1 s, 600 counts, then `holding`",
    "run-direct": "duty_cycle_sp 50: half of max_speed, duty_cycle 50, `running`",
    "stop": "with coast, brake, hold: speed 0, then state empty, empty, `holding`",
    "reset": "every setting back to the driver's default; a turning motor coasts to a stop, position 0 where it was reset",
}


def probe_command(name: str, probe: MotorProbe) -> None:
    probe.write("stop_action", "hold")
    if name == "run-forever":
        probe.write("speed_sp", 500)
        probe.write("command", name)
        probe.tick(200)
        position, state = probe.number("position"), probe.read("state")
        probe.expect(
            near(position, 1000, 5) and probe.number("speed") == 500, f"after 2 s at 500: {position}"
        )
        probe.expect(state == "running", f"state {state!r} after 2 s")
    elif name == "run-to-abs-pos":
        probe.write("speed_sp", -500)
        probe.write("position_sp", 720)
        probe.write("command", name)
        probe.tick(250)
        position, state = probe.number("position"), probe.read("state")
        probe.expect(position == 720 and state == "holding", f"ends at {position}, {state!r}")
    elif name == "run-to-rel-pos":
        probe.write("position", 100)
        probe.write("speed_sp", 400)
        probe.write("position_sp", -300)
        probe.write("command", name)
        probe.tick(150)
        position, state = probe.number("position"), probe.read("state")
        probe.expect(position == -200 and state == "holding", f"ends at {position}, {state!r}")
        # the driver's code: a run-to-rel-pos when the last command was one counts from its target
        fact = probe.data["facts"]["rel_pos_after_rel_pos"]
        probe.write("position_sp", 360)
        probe.write("command", name)
        probe.tick(10)
        probe.write("command", name)
        probe.tick(300)
        again, expected = probe.number("position"), -200 + 720
        probe.expect(
            again == expected,
            f"two run-to-rel-pos by 360 from -200, the second sent 100 ms into the first, end at {again}; at "
            f"{expected} on a brick, the first's target + 360 ({fact['file']}:{fact['line']} `{fact['source']}`)",
        )
        probe.write("stop_action", "coast")
        probe.write("command", name)
        probe.tick(200)
        coasted = probe.number("position")
        probe.write("stop_action", "hold")
        probe.write("command", "stop")
        probe.write("command", name)
        probe.tick(200)
        after_stop = probe.number("position")
        probe.expect(
            coasted > 880 + 5 and after_stop == coasted + 360,
            f"a run-to-rel-pos by 360 from 520 that coasted on to {coasted}, a stop, another by 360: ends at "
            f"{after_stop}, not where it was + 360",
        )
    elif name == "run-timed":
        probe.write("speed_sp", 400)
        probe.write("time_sp", 1500)
        probe.write("command", name)
        probe.tick(100)
        mid = probe.read("state")
        probe.tick(100)
        position, state = probe.number("position"), probe.read("state")
        probe.expect(mid == "running" and position == 600, f"{mid!r} at 1 s, {position} at the end")
        probe.expect(state == "holding", f"then {state!r}")
    elif name == "run-direct":
        probe.write("duty_cycle_sp", 50)
        probe.write("command", name)
        probe.tick(20)
        speed, duty, state = probe.number("speed"), probe.number("duty_cycle"), probe.read("state")
        half = probe.spec["max_speed"] / 2
        probe.expect(near(speed, half, 0.05 * half) and duty == 50, f"speed {speed}, duty_cycle {duty}")
        probe.expect(state == "running", f"state {state!r}")
    elif name == "stop":
        for action in probe.data["tacho_motor_class"]["stop_actions"]["names"]:
            probe.write("command", "reset")
            probe.write("stop_action", action)
            probe.write("speed_sp", 500)
            probe.write("command", "run-forever")
            probe.tick(20)
            probe.write("command", name)
            probe.tick(60)
            speed, state = probe.number("speed"), probe.read("state")
            expected = "holding" if action == "hold" else ""
            probe.expect(speed == 0 and state == expected, f"stop with {action}: speed {speed}, {state!r}")
    elif name == "reset":
        reset(probe)
    else:
        probe.expect(False, f"no probe for the command {name}")


def reset(probe: MotorProbe) -> None:
    spec = probe.spec
    defaults = {"speed_sp": 0, "position_sp": 0, "time_sp": 0, "duty_cycle_sp": 0, "ramp_up_sp": 0}
    defaults |= {"ramp_down_sp": 0, "polarity": "normal", "stop_action": "coast"}
    defaults |= {f"speed_pid/{k}": v for k, v in spec["speed_pid"].items()}
    defaults |= {f"hold_pid/{k}": v for k, v in spec["hold_pid"].items()}
    changed = {"polarity": "inversed", "stop_action": "brake"}
    for attribute in defaults:
        probe.write(attribute, changed.get(attribute, 7))
    probe.write("ramp_up_sp", 0)
    probe.write("ramp_down_sp", 0)
    probe.write("speed_sp", 300)
    probe.write("command", "run-forever")
    probe.tick(50)
    probe.write("command", "reset")
    at_reset = probe.number("position")
    probe.tick()
    rolling, state = probe.number("speed"), probe.read("state")
    wrong = {a: probe.read(a) for a, v in defaults.items() if probe.read(a) != str(v)}
    probe.expect(not wrong, f"after reset: {wrong}")
    fact = probe.data["facts"]["reset_coasts"]
    probe.expect(
        at_reset == 0 and abs(rolling) > 100 and state == "",
        f"a motor reset at speed 300: position {at_reset}, then speed {rolling}, {state!r} a tick later; on "
        f"a brick 0, then coasting ({fact['file']}:{fact['line']} `{fact['source']}`)",
    )
    probe.tick(100)
    state, position = probe.read("state"), probe.number("position")
    probe.expect(state == "" and probe.number("speed") == 0, f"1 s after reset: {state!r}")
    probe.expect(
        0 < abs(position) < 60, f"1 s after reset position reads {position}: not the roll-out counted from 0"
    )


STOP_CLAIMS = {
    "coast": "from 600: turning on after the stop, then 0; state empty",
    "brake": "from 600: 0 sooner than coasting; state empty",
    "hold": "`holding`, the position kept",
}


def stopping(probe: MotorProbe, action: str) -> list[int]:
    """The free motor at 600 stopped with `action`: its speeds over the next 600 ms."""
    probe.write("command", "reset")
    probe.write("stop_action", action)
    probe.write("speed_sp", 600)
    probe.write("command", "run-forever")
    probe.tick(30)
    probe.write("command", "stop")
    return probe.bench.speeds(probe.m, 60)


def probe_stop_action(name: str, probe: MotorProbe) -> None:
    speeds = stopping(probe, name)
    state = probe.read("state")
    if name == "coast":
        probe.expect(speeds[0] > 0 and speeds[-1] == 0, f"speeds after the stop: {speeds[:3]}…{speeds[-1]}")
        probe.expect(state == "", f"state {state!r}")
    elif name == "brake":
        stops = next(i for i, s in enumerate(speeds + [0]) if s == 0)
        coasting = stopping(probe, "coast")
        coasts = next(i for i, s in enumerate(coasting + [0]) if s == 0)
        probe.expect(stops < coasts, f"brake stops in {stops * 10} ms, coast in {coasts * 10} ms")
        probe.expect(state == "", f"state {state!r}")
    else:
        held = probe.number("position")
        probe.tick(100)
        later = probe.number("position")
        probe.expect(state == "holding" and later == held, f"{state!r}, position {held} then {later}")


STATE_CLAIMS = {
    "running": "run-forever: `running`",
    "ramping": "with ramp_up_sp: `running ramping`, then `running`",
    "holding": "stopped with hold: `holding`",
    "overloaded": "wheels pushing a wall: `running overloaded …`",
    "stalled": "wheels pushing a wall: `… stalled` after {stalled_ms} ms",
}


def probe_state(name: str, data: dict, checks: Checks, states: list[str]) -> None:
    if name in ("running", "ramping", "holding"):
        probe = MotorProbe("large", None, data, checks, states)
        if name == "ramping":
            probe.write("ramp_up_sp", 1000)
        probe.write("stop_action", "hold")
        probe.write("speed_sp", 525)
        probe.write("command", "run-forever")
        probe.tick(20)
        during = probe.read("state")
        probe.tick(60)
        after = probe.read("state")
        if name == "running":
            probe.expect(during == "running", f"run-forever: {during!r}")
        elif name == "ramping":
            probe.expect(during == "running ramping" and after == "running", f"{during!r}, then {after!r}")
        else:
            probe.write("command", "stop")
            probe.tick(5)
            held = probe.read("state")
            probe.expect(held == "holding", f"stopped with hold: {held!r}")
        return
    bench = Bench(AT_WALL_X, states=states)  # the wheels drive the robot into the wall it nearly touches
    left = bench.motor("outB")
    for port in ("outB", "outC"):
        bench.motor(port).write("speed_sp", "600")
        bench.motor(port).write("command", "run-forever")
    seen = []
    for tick in range(1, 31):
        bench.tick()
        seen.append((tick * 10, bench.read(left, "state")))
    first = next((t for t, s in seen if name in s.split()), None)
    if name == "stalled":
        stalled_ms = data["facts"]["stalled_ms"]["value"]
        checks.expect(
            first is not None and stalled_ms <= first <= stalled_ms + 30,
            f"a wheel pushing a wall reports stalled after {first} ms (the driver: {stalled_ms} ms of speed 0)",
        )
    else:
        checks.expect(first is not None, "a wheel pushing a wall never reports overloaded")


def motor_attribute_rows(data: dict, states: list[str]) -> list[Row]:
    tacho = data["tacho_motor_class"]
    rows = []
    for attribute in tacho["attributes"]:
        name, access = attribute["name"], attribute["access"]
        checks = Checks(slug(f"tacho-motor {name}"))
        for kind, motor in motor_kinds(data):
            if not checks.expect(motor is not None, f"the drivers have no motor {MOTOR_KINDS[kind][0]}"):
                continue
            what = f"{kind}: {name}"
            checks.run(what, probe_attribute, name, MotorProbe(kind, motor, data, checks, states))
            checks.run(what, check_access, name, access, MotorProbe(kind, motor, data, checks, states))
        cells = [
            f"`{name}`",
            access,
            first_sentence(attribute["description"]),
            attribute_claim(name, tacho, data["facts"]),
        ]
        rows.append(checks.row(f"tacho-motor:{name}", cells))
    return rows


def check_access(name: str, documented: str, probe: MotorProbe) -> None:
    """A read-only attribute refuses writes, a write-only one reads (EACCES), as a sysfs file does."""
    if name in ("count_per_m", "full_travel_count"):
        return
    if "write" not in documented:
        failed = error_of(lambda: probe.write(name, 0))
        probe.expect(failed == errno.EACCES, f"a write to {name} gives {errno_name(failed)}, not EACCES")
    if documented == "write-only":
        failed = error_of(lambda: probe.read(name))
        probe.expect(failed == errno.EACCES, f"a read of {name} gives {errno_name(failed)}, not EACCES")


def listed_rows(
    data: dict, attribute: str, prefix: str, claims: dict, probe: Callable, states: list[str]
) -> list[Row]:
    """A row for each value the driver lists for a motor attribute (command, stop_action), on each kind."""
    values = next(a["values"] for a in data["tacho_motor_class"]["attributes"] if a["name"] == attribute)
    rows = []
    for value in values:
        name = value["name"]
        checks = Checks(slug(f"{prefix} {name}"))
        for kind, motor in motor_kinds(data):
            if motor is not None:
                checks.run(f"{kind}: {name}", probe, name, MotorProbe(kind, motor, data, checks, states))
        rows.append(
            checks.row(f"{prefix}:{name}", [f"`{name}`", first_sentence(value["text"]), claims.get(name, "")])
        )
    return rows


def state_rows(data: dict, states: list[str]) -> list[Row]:
    values = next(a["values"] for a in data["tacho_motor_class"]["attributes"] if a["name"] == "state")
    stalled_ms = data["facts"]["stalled_ms"]["value"]
    rows = []
    for value in values:
        name = value["name"]
        checks = Checks(slug(f"state {name}"))
        checks.run(name, probe_state, name, data, checks, states)
        claim = STATE_CLAIMS.get(name, "").format(stalled_ms=stalled_ms)
        rows.append(checks.row(f"state:{name}", [f"`{name}`", first_sentence(value["text"]), claim]))
    return rows


def state_order_row(data: dict, states: list[str]) -> Row:
    """The flags of `state` come in the driver's order (state_show walks tacho_motor_states)."""
    order = data["tacho_motor_class"]["states"]["names"]
    checks = Checks("state-flag-order")
    for state in dict.fromkeys(states):
        flags = state.split()
        checks.expect(all(f in order for f in flags), f"`{state}` has a flag the driver does not have")
        checks.expect(
            flags == sorted(flags, key=lambda f: order.index(f) if f in order else 99),
            f"`{state}`: not the driver's order",
        )
    claim = f"every state the probes read lists its flags in this order: `{' '.join(order)}`"
    return checks.row("state:order", ["(the order)", "(state_show writes them in the driver's order)", claim])


def not_simulated_rows(data: dict) -> list[Row]:
    """The LEGO devices the drivers know that ev3sim2d has no kind for."""
    ours = {cls.DRIVER for cls in BUILT_IN} | {driver for driver, _speed, _kp in MOTOR_KINDS.values()}
    rows = []
    for device in data["sensors"] + data["motors"]:
        if device["driver"] in ours:
            continue
        checks = Checks("not-simulated")
        checks.expect(False, f"{device['driver']}: no kind of device in ev3sim2d")
        rows.append(
            checks.row(
                f"not-simulated:{device['driver']}",
                [
                    f"`{device['driver']}`",
                    f"{device['part_name']} ({device['part_number']})",
                    f"`{device['file']}`",
                ],
            )
        )
    return rows


def first_sentence(text: str) -> str:
    """The first sentence of a driver's description, its RST marks made Markdown's."""
    text = text.replace("``", "`").replace("*", "")
    found = re.search(r"(?<!e\.g)\.\s+(?=[A-Z`])", text)
    return text if found is None else text[: found.start() + 1]
