"""What a brick sends, as a determined student would write it to hurt the simulator, run for real.

Everything a brick sends is the student's to choose: these programs reach into the shim's internals (the
brick's link, `ev3dev2._link._backend`, and its connection) to send what no honest program sends, or a
brick is played by hand on a real Session, or on a real `ev3sim2d serve` over TCP.  Each class of attack
meets a rule, enforced in one place:

1. values (devices/device.py `parse_int`, each device's write rules): every written value is checked as
   its driver checks it, within a C int's range; nothing a brick writes raises but the device's OSError;
2. budgets (results/trace.py, enforced by simulator/brick_port.py): what one brick makes the simulator
   keep and do is bounded per run; past a budget that brick's run ends, the reason naming the budget;
3. containment (simulator/session.py `Session._apply`): whatever goes wrong applying one brick's ops
   ends that brick, never the world, and is reported loudly;
4. hangs (session.py `_stalled`): a brick whose clock stands still is hung, whatever it sends;
5. rendering (render/timeline.py, audio.py): a trace's sounds play within the budgets, quickly.

A test passes when the honest outcome holds: the attacker's run ends with its reason; an honest robot in
the same world finishes, with the very record (poses, lines, events) it has beside a robot that stands
still; the simulator process stays under MEMORY_CEILING_MB (its own peak resident memory, measured by
the process itself with getrusage(RUSAGE_SELF) as it exits); a video of the attacker's trace is made in
under RENDER_CEILING_S.
"""

from __future__ import annotations

import errno
import hashlib
import itertools
import json
import math
import os
import re
import socket
import subprocess
import sys
import textwrap
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from ev3sim2d.devices.brick_parts import Battery, Led
from ev3sim2d.devices.device import C_INT_MAX, C_INT_MIN, C_ULONG_MAX
from ev3sim2d.devices.motor import OVERLOADED, STALLED, TachoMotor
from ev3sim2d.devices.registry import SENSORS
from ev3sim2d.devices.sensor import SAMPLES_PER_TICK
from ev3sim2d.protocol import PROTOCOL, Channel, ProtocolError, decode, encode
from ev3sim2d.protocol.joining import join_message
from ev3sim2d.render.audio import sound_track
from ev3sim2d.render.timeline import Timeline, sound_spans
from ev3sim2d.results.trace import (
    EVENTS,
    KEYS,
    LCD_FRAMES,
    SOUND_NOTES,
    SOUND_SECONDS,
    Trace,
)
from ev3sim2d.simulator.brick_port import BrickPort, OverBudget
from ev3sim2d.simulator.session import Session
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.maze_file import parse_maze
from tests.grading.lesson_maker import write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]
MEMORY_CEILING_MB = 300  # the simulator's peak resident memory under any attack (an honest run: about 50)
RENDER_CEILING_S = 5.0  # a video of an attacker's trace (or a hand-made one), at 320x180
TICK = 10_000

# The simulator, its peak resident memory said on stderr as it exits (the bricks are other processes):
# VmHWM (getrusage's ru_maxrss would count the peak of the process that started it, kept across exec);
# without /proc, ru_maxrss (in bytes on macOS), and on Windows, which has neither, the peak working set.
MEASURED = """\
import runpy, sys
def peak_kb():
    try:
        with open("/proc/self/status") as status:
            return next(int(line.split()[1]) for line in status if line.startswith("VmHWM:"))
    except (OSError, StopIteration):
        pass
    try:
        import resource
    except ImportError:
        return windows_peak_kb()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak // 1024 if sys.platform == "darwin" else peak
def windows_peak_kb():
    import ctypes
    from ctypes import wintypes
    sizes = ("PeakWorkingSetSize WorkingSetSize QuotaPeakPagedPoolUsage QuotaPagedPoolUsage "
             "QuotaPeakNonPagedPoolUsage QuotaNonPagedPoolUsage PagefileUsage PeakPagefileUsage").split()
    class Counters(ctypes.Structure):  # PROCESS_MEMORY_COUNTERS (psapi.h)
        _fields_ = [("cb", wintypes.DWORD), ("PageFaultCount", wintypes.DWORD)] + [(n, ctypes.c_size_t) for n in sizes]
    kernel32 = ctypes.WinDLL("kernel32", use_last_error=True)
    kernel32.GetCurrentProcess.restype = wintypes.HANDLE
    kernel32.K32GetProcessMemoryInfo.argtypes = [wintypes.HANDLE, ctypes.c_void_p, wintypes.DWORD]
    counters = Counters(cb=ctypes.sizeof(Counters))
    if not kernel32.K32GetProcessMemoryInfo(kernel32.GetCurrentProcess(), ctypes.byref(counters), counters.cb):
        raise ctypes.WinError(ctypes.get_last_error())
    return counters.PeakWorkingSetSize // 1024
sys.argv = ["ev3sim2d", *sys.argv[1:]]
try:
    runpy.run_module("ev3sim2d", run_name="__main__", alter_sys=True)
finally:
    print("PEAK_KB", peak_kb(), file=sys.stderr)
"""

# robot 2 of line-shared, half the world away from robot 1: it drives, prints, beeps and lights up
HONEST = """\
import time
from ev3dev2.led import Leds
from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
from ev3dev2.sound import Sound
tank = MoveTank(OUTPUT_B, OUTPUT_C)
Sound().beep()
Leds().set_color("LEFT", "RED")
tank.on(20, 20)
for second in range(3):
    print("second", second)
    time.sleep(1)
tank.off()
print("done")
"""
HONEST_UNTIL_S = 3.0  # its record is compared up to here (a run goes on to the last brick's time)
STILL = 'print("standing still")\n'

# What every attacking program starts with: the brick's own link, and a way to send ops past its checks.
PRELUDE = """\
import builtins
import time
from ev3dev2 import _link
builtins.__ev3sim2d_line__ = True.__bool__  # its own lines cost the attacker no time: it forges its clock
link = _link._backend
def now():
    return link.scheduler.now_us
def send(*ops):
    link.channel.send(["ops", list(ops)])
def ask(*ops):
    return link.ask(list(ops))
def pause():  # real time passes, the brick's clock does not: a loop that computes
    for _ in range(50_000):
        pass
"""


def robot_record(trace: Trace, index: int, until_s: float = HONEST_UNTIL_S) -> str:
    """One robot's own record up to until_s: poses, motors, lines, events and sensor samples."""
    h = hashlib.sha256()
    ticks = int(np.searchsorted(np.asarray(trace.times), until_s + 1e-9))
    h.update(np.round(trace.motion()[:ticks, trace.robot_columns(index)] * 1e4).astype(np.int64).tobytes())
    mine = [
        [round(o.t_s, 6), o.stream, o.text] for o in trace.output if o.robot == index and o.t_s <= until_s
    ]
    h.update(json.dumps(mine).encode())
    h.update(json.dumps([e for e in trace.events if e[1] == index and e[0] <= until_s], default=str).encode())
    h.update(json.dumps([s for s in trace.sensor_samples if s[1] == index and s[0] <= until_s]).encode())
    return h.hexdigest()[:16]


@dataclass
class Ran:
    """An `ev3sim2d run` (or serve) of programs: what it said, left and used."""

    rc: int
    stdout: str
    stderr: str
    summary: dict
    trace: Trace | None
    wall_s: float
    peak_mb: float


def _env() -> dict:
    return {**os.environ, "PYTHONHASHSEED": "0", "PYTHONUNBUFFERED": "1"}


def _peak_mb(stderr: str) -> float:
    found = re.findall(r"PEAK_KB (\d+)", stderr)
    assert found, stderr[-3000:]
    return int(found[-1]) / 1024


def run_cli(tmp_path: Path, *programs: str, time_s: float = 10, hang_after_s: float = 1.0) -> Ran:
    """`ev3sim2d run` of these program texts in line-shared (one robot each), measured."""
    paths = []
    for i, source in enumerate(programs):
        path = tmp_path / f"program{i + 1}.py"
        path.write_text(textwrap.dedent(source))
        paths.append(str(path))
    summary, trace = tmp_path / "summary.json", tmp_path / "trace.npz"
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-c", MEASURED, "run", *paths, "--maze", "line-shared", "--time", str(time_s),
         "--hang-after", str(hang_after_s), "--summary", str(summary), "--trace", str(trace)],
        capture_output=True, text=True, cwd=tmp_path, env=_env(), timeout=300,
    )  # fmt: skip
    wall = time.perf_counter() - started
    assert summary.exists(), done.stderr[-3000:]
    return Ran(
        done.returncode,
        done.stdout,
        done.stderr,
        json.loads(summary.read_text()),
        Trace.load(trace),
        wall,
        _peak_mb(done.stderr),
    )


@pytest.fixture(scope="module")
def alone(tmp_path_factory) -> Ran:
    """The honest robot beside one that stands still: the record every attack must leave it."""
    return run_cli(tmp_path_factory.mktemp("alone"), STILL, HONEST)


def render_s(trace: Trace, path: Path) -> float:
    """Seconds to make a small video of the trace (its sound track included)."""
    from ev3sim2d.render.video import VideoOptions, write_video

    started = time.perf_counter()
    write_video(trace, path, VideoOptions(fps=10, speed=4.0, size=(320, 180)), progress=False)
    return time.perf_counter() - started


def assert_contained(ran: Ran, alone: Ran, reason: str, tmp_path: Path) -> None:
    """The honest outcome of an attack by robot 1 on a run beside the honest robot 2."""
    assert reason in ran.summary["reason"], ran.summary["reason"]
    assert ran.summary["reason"].startswith(("budget:", "protocol:", "stopped:")), ran.summary["reason"]
    assert "robot2] done" in ran.stdout, ran.stdout[-2000:] + ran.stderr[-2000:]
    assert robot_record(ran.trace, 1) == robot_record(alone.trace, 1)
    assert ran.peak_mb < MEMORY_CEILING_MB, f"the simulator grew to {ran.peak_mb:.0f} MB"
    assert "Traceback" not in ran.stderr, ran.stderr[-3000:]
    assert render_s(ran.trace, tmp_path / "attack.mp4") < RENDER_CEILING_S


# ================================================================ fake bricks on a real Session


def world_with(n_robots: int = 2, width: int = 20):
    starts = "\n".join(f"  - {{x_cm: {60 + 60 * i}, y_cm: 120, heading_deg: 0}}" for i in range(n_robots))
    rows = "\n".join("  " + r for r in ["#" * width] + ["#" + "." * (width - 2) + "#"] * 18 + ["#" * width])
    return parse_maze(f"title: t\ncell_cm: 12\ngrid: |\n{rows}\nstart:\n{starts}\n", "<test>")


class FakeBrick:
    """A brick played by hand on a real connection: a thread sends what it is given (a number: sleep that
    long first), another reads and forgets what the simulator sends, so a flood never blocks the test."""

    def __init__(self, messages, read: bool = True) -> None:
        ours, theirs = socket.socketpair()
        self.port_channel = Channel(ours)
        self.end = Channel(theirs)
        self.stopped = threading.Event()
        self.sent = 0
        threading.Thread(target=self._send, args=(messages,), daemon=True).start()
        if read:
            threading.Thread(target=self._read, daemon=True).start()

    def _send(self, messages) -> None:
        for message in messages:
            if self.stopped.is_set():
                return
            try:
                if isinstance(message, (int, float)):
                    time.sleep(message)
                elif isinstance(message, bytes):
                    self.end.send_bytes(message)
                else:
                    self.end.send(message)
                self.sent += 1
            except (ProtocolError, OSError):
                return

    def _read(self) -> None:
        while not self.stopped.is_set():
            try:
                self.end.receive(timeout_s=0.05)
            except (ProtocolError, OSError, ValueError):
                return

    def close(self) -> None:
        self.stopped.set()
        self.end.close()


def play(bricks: list[FakeBrick], limit_us: int = 3_000_000, hang_after_s: float = 0.5):
    """A real Session of these bricks, one robot each, run to its end; (session, ports, sim)."""
    world = world_with(len(bricks))
    sim = Simulation(world, [(f"r{i}", world.robot, world.starts[i]) for i in range(len(bricks))])
    ports = [BrickPort(i, sim.robots[i], b.port_channel, sim.trace, []) for i, b in enumerate(bricks)]
    session = Session(sim, ports, limit_us, hang_after_s)
    try:
        session.run()
    finally:
        for brick in bricks:
            brick.close()
    return session, ports, sim


def drive(ticks: int, first: int = 0) -> list:
    ops = [["k", 0, "tacho-motor", "motor1", "speed_sp"], ["k", 1, "tacho-motor", "motor1", "command"]]
    ops += [["W", 0, "300"], ["W", 1, "run-forever"], ["q"]]
    return ["ops", ops + [["t", TICK * (first + i + 1)] for i in range(ticks)]]


def honest_brick(ticks: int = 100) -> FakeBrick:
    return FakeBrick([drive(ticks), ["end", {"t_us": ticks * TICK, "status": "finished"}]])


def still_brick() -> FakeBrick:
    return FakeBrick([["end", {"t_us": 0, "status": "finished"}]])


def forever(*messages, every_s: float = 0.01):
    """These messages again and again, every_s apart (the generator a flooding brick sends)."""
    while True:
        for message in messages:
            yield message
            if every_s:
                yield every_s


@pytest.fixture(scope="module")
def honest_alone_poses():
    _, ports, sim = play([still_brick(), honest_brick()])
    assert ports[1].end["status"] == "finished"
    return sim.trace.poses(1)


def assert_honest_finished(ports, sim, honest_alone_poses, index: int = 1) -> None:
    assert ports[index].gone is None and ports[index].end["status"] == "finished"
    np.testing.assert_array_equal(sim.trace.poses(index)[: len(honest_alone_poses)], honest_alone_poses)


# ===================================================================================== 1. values

HOSTILE_VALUES = [
    "9" * 4000,  # the gain that passed the old check and overflowed the world's tick
    "-" + "9" * 4000,
    "9" * 5000,  # (past Python's own limit on digits)
    "1" + "0" * 4097,  # (past a sysfs page)
    str(C_INT_MAX + 1),
    str(C_INT_MIN - 1),
    str(C_ULONG_MAX + 1),
    str(C_INT_MAX),
    str(C_INT_MIN),
    "-0",
    "+0",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e308",
    "1e309",
    "-1e308",
    "0.5",
    "0x7fffffff",
    "1_000",
    "٣",
    "１２",
    "\x00",
    "\x11",
    "\ud800",
    "\U0010ffff",
    "",
    " " * 100,
    "run-forever" + " " * 10_000,
    "x" * 1_000_000,
    "[none]",
    "US-SI-CM",
]


def every_device():
    """One of every kind of device, as the simulator makes them."""
    spec = SimpleNamespace(radius_cm=5.0, angle_deg=0.0, aim_deg=0.0, noise=0.0, facing="forward", options={})
    around = SimpleNamespace(heading_rad=0.0, turn_rate=0.0, tick=0, sound_until_tick=0, others=[], rng=None)
    around.sensor_pose = lambda mount: (0.0, 0.0, 0.0)
    around.ray = lambda x, y, direction, max_cm: None
    around.near = lambda x, y, reach: False
    around.touches_segment = lambda *args: False
    floor = SimpleNamespace(
        cell_cm=10.0, width=1, height=1, reflected=[[50]], color_id=[[6]], raw_rgb=[[(1, 1, 1)]]
    )
    devices = [TachoMotor("ev3-ports:outA", "large"), TachoMotor("ev3-ports:outB", "medium")]
    for kind in SENSORS.values():
        takes_floor = "floor" in kind.__init__.__code__.co_varnames
        devices.append(
            kind("ev3-ports:in1", spec, around, floor) if takes_floor else kind("ev3-ports:in1", spec, around)
        )
    return [*devices, Led("led0:green:brick-status"), Battery()]


@pytest.mark.parametrize("device", every_device(), ids=lambda d: type(d).__name__)
def test_every_written_attribute_of_every_device_kind_raises_nothing_but_oserror(device):
    """Any text in every attribute a device has (and some it has not): EINVAL (or the attribute's own
    errno), never another exception, and what the device keeps stays a C value a driver could hold."""
    attributes = [*device.writers, *device.readers, "no-such-attribute"]
    for attribute in attributes:
        for value in HOSTILE_VALUES:
            try:
                device.write(attribute, value)
            except OSError as err:
                assert err.errno in (errno.EINVAL, errno.ENOENT, errno.EACCES), (attribute, value[:20], err)
                assert len(str(err)) < 200
    for name, value in vars(device).items():
        if type(value) is int:
            assert C_INT_MIN <= value <= C_ULONG_MAX, (name, value)


def test_every_integer_rule_is_a_range_its_driver_can_hold():
    """A brick checks writes with these rules: none is unbounded, none wider than what its driver parses
    the text into (a C int; an LED's brightness an unsigned long, 32 bits on the EV3)."""
    for device in every_device():
        for attribute, rule in device.write_rules.items():
            assert attribute in device.writers, (type(device).__name__, attribute)
            if rule[0] == "int":
                low, high = rule[1], rule[2]
                assert low is not None and high is not None, (type(device).__name__, attribute)
                assert C_INT_MIN <= low <= high <= C_ULONG_MAX, (type(device).__name__, attribute)


def test_the_largest_values_the_drivers_take_keep_the_world_ticking():
    """Every integer attribute at its largest and smallest value, every command, a robot pushing a wall
    for seconds (the speed PID's arithmetic, where a 4000-digit gain once overflowed): the world ticks."""
    world = world_with(1, width=8)
    sim = Simulation(world, [("r", world.robot, world.starts[0])])
    robot = sim.robots[0]
    seen = 0
    for extreme in ("low", "high"):
        for motor in robot.motors.values():
            for attribute, rule in motor.write_rules.items():
                if rule[0] == "int":
                    motor.write(attribute, str(rule[1] if extreme == "low" else rule[2]))
            motor.write("speed_sp", str(motor.max_speed))
            motor.write("ramp_up_sp", "0")
            motor.write("ramp_down_sp", "0")
        for command in ("run-forever", "run-to-abs-pos", "run-to-rel-pos", "run-timed", "run-direct", "stop"):
            for motor in robot.motors.values():
                motor.write("command", command)
            for _ in range(60):
                sim.tick((sim.ticks + 1) * TICK)
                for motor in robot.motors.values():
                    seen |= motor.state_bits
    assert sim.ticks == 2 * 6 * 60
    assert np.isfinite(sim.trace.motion()).all()
    assert seen & OVERLOADED and seen & STALLED  # the speed PID pushed against the wall


GAIN_ATTACK = (
    PRELUDE
    + """\
from ev3dev2.motor import LargeMotor, MoveTank, OUTPUT_B, OUTPUT_C
motor = LargeMotor(OUTPUT_B)
key = link._key("tacho-motor", motor._device_name, "speed_pid/Kp")
for value in ("9" * 4000, "-" + "9" * 4000, "2147483648", "1e308", "nan", "inf", "٣" * 4000):
    answer = ask(["W", key, value])[0]  # past the brick's own check
    print("refused" if answer[0] and answer[0][0] == 22 else f"taken {answer}")
    send(["w", key, value])  # and on the hot path, which does not answer
print("gain", link.read("tacho-motor", motor._device_name, "speed_pid/Kp"))
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on(-100, -100)  # backwards into the wall behind: the speed PID works hard, as it did when it overflowed
time.sleep(3)
tank.off()
print("survived")
"""
)


def test_a_4000_digit_gain_is_refused_as_the_driver_refuses_it_and_serve_runs_on(tmp_path):
    """The incident: a gain of 4000 digits passed the write check and overflowed inside the world's
    tick, which ended `serve` and every joined student's run.  Now the simulator refuses it (EINVAL, as
    the driver's kstrtoint does), on both write paths; the program drives on, and so does the world."""
    served = Served(tmp_path, "--robots", "2", "--time", "10", "--summary", "served.json")
    try:
        attacker = _join(served.address, _program(tmp_path, "gain.py", GAIN_ATTACK), "--robot", "1", tmp_path)
        honest = _join(served.address, _program(tmp_path, "honest.py", HONEST), "--robot", "2", tmp_path)
        out1, err1 = attacker.communicate(timeout=120)
        out2, err2 = honest.communicate(timeout=120)
        assert served.finish() == 0, served.log()
    finally:
        served.stop()
    assert out1.count("refused") == 7 and "gain 1000" in out1 and "survived" in out1, out1 + err1
    assert "] done" in out2 and honest.returncode == 0 and attacker.returncode == 0, err1 + err2
    assert re.search(r"robot1 \(gain[^)]*\): finished", served.log()), served.log()
    assert re.search(r"robot2 \(honest[^)]*\): finished", served.log()), served.log()
    assert served.peak_mb() < MEMORY_CEILING_MB


HOSTILE_WRITER = PRELUDE + textwrap.dedent(
    """\
    import json
    answers, taken = {}, []
    for cls in ("tacho-motor", "lego-sensor", "leds"):
        for name in _link.list_device_names(cls, "*"):
            for attribute in ("speed_sp", "position_sp", "time_sp", "duty_cycle_sp", "ramp_up_sp",
                              "ramp_down_sp", "position", "hold_pid/Kp", "speed_pid/Ki", "speed_pid/Kd",
                              "command", "polarity", "stop_action", "mode", "brightness", "trigger",
                              "direct", "value0"):
                key = link._key(cls, name, attribute)
                for value in ("9" * 4000, "2147483648", "-2147483649", "4294967296", "1e308", "nan",
                              "inf", "-inf", "-0.0", "\\x00", "x" * 100000):
                    error = ask(["W", key, value])[0][0]
                    answers[str(error and error[0])] = answers.get(str(error and error[0]), 0) + 1
                    if error is None:
                        taken.append([attribute, value])
                time.sleep(0.001)
    print(json.dumps([answers, taken]))
    time.sleep(0.5)
    print("still running")
    """
)


def test_hostile_numbers_in_every_attribute_through_a_real_brick_are_refused_and_the_run_goes_on(run):
    """A program writes every number a driver cannot hold into every attribute of every device of its
    robot, past its brick's own checks: each is refused, none taken, and the run goes on to its end."""
    result = run(HOSTILE_WRITER)
    assert result.status == "finished", result.reason
    printed = [line.text for line in result.trace.output]
    assert printed[-1] == "still running"
    answers, taken = json.loads(printed[0])
    # not one hostile value was taken, but the one an LED's brightness (an unsigned long) may hold
    assert taken == [["brightness", "2147483648"]] * 4, taken
    assert {int(e) for e in answers if e != "None"} <= {errno.EINVAL, errno.ENOENT, errno.EACCES}, answers
    assert answers[str(errno.EINVAL)] > 500


# ==================================================================================== 2. budgets

BUDGET_ATTACKS = {
    # notes of notes (the attack that grew a grader to gigabytes), a million notes in one beep, a note
    # list inside every kind of sound
    "notes": (
        """\
        deep = [{"length_ms": 1, "notes": [{"notes": [{}] * 100}] * 100}] * 100  # a million notes of notes
        link.call("sound", "beep", {"notes": deep})
        link.call("sound", "beep", {"notes": [{"length_ms": 1}] * 400_000})  # 400,000 notes in one beep
        small = [{"length_ms": 1, "notes": [{"notes": [{}] * 10}] * 10}] * 100
        while True:
            for kind in ("beep", "speak", "play_file", "set_volume", "tone"):
                link.call("sound", kind, {"notes": small, "text": "x"})
            time.sleep(0.01)
        """,
        "SOUND_NOTES",
    ),
    # a hundred notes of a hundred repeats each, a minute long: hours of sound for a video to synthesise
    "repeats": (
        """\
        notes = [{"frequency": 440 + i, "length_ms": 60000, "repeats": 100, "delay_ms": 0} for i in range(100)]
        while True:
            link.call("sound", "beep", {"notes": notes, "duration": 1e308})
            time.sleep(0.01)
        """,
        "SOUND_SECONDS",
    ),
    # speech and sound files that last an hour each, without waiting for them
    "speech": (
        """\
        while True:
            link.call("sound", "speak", {"text": "y" * 10_000, "duration": 3600.0})
            link.call("sound", "play_file", {"wav_file": "/z" * 10_000, "duration": float("inf")})
            time.sleep(0.01)
        """,
        "SOUND_SECONDS",
    ),
    # sounds that cost nothing and say nothing, as fast as the clock lets them through
    "sounds": (
        """\
        t = now()
        while True:
            t += 100_000
            send(*[["c", t, "sound", ["set_volume", {"pct": i % 100}]] for i in range(1000)])
        """,
        "EVENTS",
    ),
    # the LEDs blinking a thousand times a millisecond
    "leds": (
        """\
        key = link._key("leds", "led0:red:brick-status", "brightness")
        link.flush()
        t = now()
        while True:
            t += 100_000
            send(*[["w", key, str(255 * (i % 2)), t] for i in range(1000)])
        """,
        "EVENTS",
    ),
    # a new LCD frame at every refresh of the screen, each different, for minutes of virtual time
    "lcd": (
        """\
        t, n = now(), 0
        while True:
            t, n = t + 50_000, n + 1
            send(["c", t, "display", [(n.to_bytes(4, "big") + bytes(178 * 128 - 4)).hex()]])
        """,
        "LCD_FRAMES",
    ),
    # one line of megabytes
    "printed_bytes": (
        """\
        while True:
            link.output(now(), "stdout", "x" * 3_000_000)
            time.sleep(0.001)
        """,
        "PRINTED_BYTES",
    ),
    # print() in a loop: each line costs the brick 1 ms, so its clock runs, but the lines pile up
    "printed_lines": (
        """\
        n = 0
        while True:
            print(n)
            n += 1
        """,
        "PRINTED_LINES",
    ),
    # a key for every attribute a name could have
    "keys": (
        """\
        for i in range(KEYS + 1):
            link._key("tacho-motor", "motor1", f"attribute{i}")
            if i % 1000 == 0:
                link.flush()
                time.sleep(0.1)
        link.flush()
        time.sleep(1)
        """,
        "KEYS",
    ),
    # ops that cost the brick nothing, its clock creeping on by a microsecond each
    "creep": (
        """\
        t = now()
        while True:
            t += 1
            send(["@", t])
        """,
        "OPS_PER_SECOND",
    ),
    # a message nested deeper than any parser's stack
    "deep_json": (
        """\
        link.channel.send_bytes(b'["ops",' + b"[" * 200_000 + b"]" * 200_000 + b"]\\n")
        time.sleep(5)
        """,
        "not a JSON message",
    ),
    # the whole shared ring one message, nested deeper than any parser's stack, written where the simulator
    # takes a whole message straight from shared memory (SharedChannel.pending); over a socket, the same bytes
    "deep_ring": (
        """\
        RING = 1 << 20
        ch = link.channel
        time.sleep(0.5)
        link.flush()
        if hasattr(ch, "_words"):
            pad = RING - ch._written % RING  # a heartbeat, padded with spaces to the ring's end
            pad += RING if pad < 64 else 0
            head = b'["ops",[["@",%d]]' % now()
            ch.send_bytes(head + b" " * (pad - len(head) - 2) + b"]\\n")
            while ch._words[ch._out[1]] != ch._written:  # (its clock stands still: nothing else is sent)
                pause()
        ch.send_bytes(b"[" * (RING - 1) + b"\\n")
        time.sleep(5)
        """,
        "not a JSON message",
    ),
    # quiet waits (protocol 2, op u) that lie: back in time, past any run, on a value never read, malformed
    "quiet_backwards": (
        """\
        time.sleep(0.5)
        send(["u", now() - 20_000, now() - 10_000, 0, 0])
        time.sleep(5)
        """,
        "goes back in time",
    ),
    "quiet_for_ever": (
        """\
        time.sleep(0.5)
        send(["u", now() + 10_000, 10**30, 0, 0])
        time.sleep(5)
        """,
        "goes back in time",
    ),
    "quiet_unwatched": (
        """\
        time.sleep(0.5)
        t = now() - now() % 10_000 + 10_000
        send(["u", t, t + 1_000_000, 987_654, 0])
        time.sleep(5)
        """,
        "a quiet wait",
    ),
    "quiet_malformed": (
        """\
        time.sleep(0.5)
        send(["u", "soon", None])
        time.sleep(5)
        """,
        "a quiet wait is [u, first tick, last tick, key, value]",
    ),
    # requests that are never collected: answers the simulator would keep for ever
    "requests": (
        """\
        key = link._key("tacho-motor", "motor1", "position")
        link.flush()
        while True:
            send(*[["R", key]] * 1000)
            time.sleep(0.001)
        """,
        "requests in a batch without its [q]",
    ),
}


@pytest.mark.parametrize("attack", list(BUDGET_ATTACKS))
def test_a_brick_past_a_budget_ends_alone_and_small(attack, alone, tmp_path):
    """Each attack ends the attacker's run with a reason naming what it broke; the honest robot beside it
    runs as it runs beside a robot that stands still; the simulator stays small, the video quick."""
    source, reason = BUDGET_ATTACKS[attack]
    program = PRELUDE + f"KEYS = {KEYS}\n" + textwrap.dedent(source)
    time_s = 200 if attack in ("lcd", "printed_lines") else 10
    ran = run_cli(tmp_path, program, HONEST, time_s=time_s, hang_after_s=3.0)
    assert_contained(ran, alone, reason, tmp_path)


def test_the_budgets_leave_room_for_what_real_programs_do(run):
    """A melody, a sensor log every 10 ms for 60 s, a screen drawn every tick, LEDs blinking: all within
    the budgets, nothing lost."""
    result = run(
        """\
        import time
        from ev3dev2.display import Display
        from ev3dev2.led import Leds
        from ev3dev2.sensor.lego import ColorSensor
        from ev3dev2.sound import Sound
        sound, leds, lcd, color = Sound(), Leds(), Display(), ColorSensor()
        sound.play_song([("C4", "e"), ("D4", "e"), ("E4", "q"), ("C4", "e")] * 25)
        start = time.time()
        n = 0
        while time.time() - start < 60:
            light = color.reflected_light_intensity
            print(f"t={time.time() - start:.3f} light={light} n={n}")
            lcd.text_pixels(f"{n} {light}", clear_screen=True)
            lcd.update()
            if n % 10 == 0:
                leds.set_color("LEFT", "RED" if n % 20 else "GREEN")
            n += 1
            time.sleep(0.01 - 0.003)
        print("logged", n)
        """,
        time_limit_s=100,
    )
    assert result.status == "finished", result.reason
    assert result.trace.output[-1].text.startswith("logged") and len(result.trace.output) > 4000
    lcd = [e for e in result.trace.events if e[2] == "lcd"]
    assert len(lcd) > 4000 and 500 < len(result.trace.lcd_frames) <= LCD_FRAMES / 2
    assert len(result.trace.events) < EVENTS / 2


def test_what_a_brick_says_of_itself_is_kept_short():
    """Megabytes in an end message's error, or in a hello's sandbox report, are cut to what a report shows."""
    world = world_with(1)
    sim = Simulation(world, [("r", world.robot, world.starts[0])])
    port = BrickPort(0, sim.robots[0], None, sim.trace, [])
    huge = "e" * 5_000_000
    port.hello = {
        "protocol": PROTOCOL,
        "python": huge,
        "sandbox": {f"layer{i}" + huge: huge for i in range(3)},
        "x": huge,
    }
    port.end = {
        "t_us": 0,
        "status": huge,
        "error": {"type": huge, "message": huge, "traceback": huge, "more": huge},
    }
    assert len(json.dumps(port.hello)) < 5_000 and len(json.dumps(port.end)) < 30_000
    assert port.end["error"]["message"] == "e" * 2000


def test_an_led_written_again_and_a_screen_drawn_again_are_not_kept_again():
    """The same brightness again is no LED change.  The screen shows a new picture once a refresh (50 ms)
    at most: draws within a refresh keep one picture (the last), the same picture again is not kept
    again, and past LCD_DRAWS_PER_REFRESH draws a refresh's last event moves: honest loops stay far from
    the budgets, and the trace still shows every picture the screen could show."""
    world = world_with(1)
    sim = Simulation(world, [("r", world.robot, world.starts[0])])
    port = BrickPort(0, sim.robots[0], SimpleNamespace(send=lambda m: None), sim.trace, [])
    white, black = "ff" * 178 * 128, "00" * 178 * 128
    ops = [["k", 0, "leds", "led0:red:brick-status", "brightness"]]
    ops += [["w", 0, "255", 1000 + i] for i in range(100)]
    ops += [["c", 2000 + i, "display", [white if i % 2 else black]] for i in range(100)]  # one refresh
    ops += [["c", 60_000 + i, "display", [black]] for i in range(100)]  # the next: black again
    ops += [["c", 200_000, "display", [white]]]
    port.accept(["ops", ops])
    port.run_ops(0)
    events = sim.trace.events
    assert [e[2] for e in events] == ["leds"] + ["lcd"] * 9
    assert [e[3]["frame"] for e in events[1:]] == [0] * 4 + [1] * 4 + [2]
    assert sim.trace.lcd_frames == [bytes.fromhex(white), bytes.fromhex(black), bytes.fromhex(white)]
    assert events[4][0] == 0.002099 and events[8][0] == 0.060099  # the last draw of each refresh
    assert port.lcd_frames == 3 and port.events == 10


def test_a_sensor_measured_thousands_of_times_a_tick_keeps_a_few_samples_a_tick_and_the_last_one():
    """A lying brick changes a sensor's mode and reads it again and again without its clock moving (an
    honest program's mode write costs 3 ms, so it measures at most five times a tick).  Each measurement is
    served, but the record keeps SAMPLES_PER_TICK of a tick at most, the tick's last in the last place: the
    trace grows with virtual time only, and says what the sensor last measured in each tick."""
    world = world_with(1)
    sim = Simulation(world, [("r", world.robot, world.starts[0])])
    replies = []
    port = BrickPort(0, sim.robots[0], SimpleNamespace(send=replies.append), sim.trace, [])
    modes = ["COL-AMBIENT", "COL-REFLECT", "COL-COLOR", "RGB-RAW"]
    ops = [["k", 0, "lego-sensor", "sensor2", "mode"], ["k", 1, "lego-sensor", "sensor2", "value0"]]
    ops += [["W", 0, "COL-REFLECT"], ["R", 1]]  # (the first write asks for the rule; the read subscribes)
    ticks, flips = 3, 2_000
    for tick in range(ticks):
        for i in range(flips):
            ops += [["w", 0, modes[i % len(modes)]], ["q"]]  # each reply carries value0 measured afresh
        ops += [["t", TICK * (tick + 1)]]
    port.accept(["ops", ops])
    for tick in range(ticks):  # the world steps to each tick marker, as the session steps it
        port.run_ops(TICK * tick)
        assert port.marker == TICK * (tick + 1) and port.gone is None
        sim.tick(port.marker)
        port.marker = None
    assert len(replies) == ticks * flips and all(r[0] == "reply" and len(r[2]) == 1 for r in replies)
    samples = sim.robots[0].sensors["in3"].samples
    per_tick = {}
    for tick, mode, values in samples:
        per_tick.setdefault(tick, []).append((mode, values))
    assert sorted(per_tick) == list(range(ticks)) and len(samples) == ticks * SAMPLES_PER_TICK
    last_mode = modes[(flips - 1) % len(modes)]  # RGB-RAW: four values, the last is the LEDs-off reading
    for tick, kept in per_tick.items():
        assert len(kept) == SAMPLES_PER_TICK
        assert kept[-1][0] == last_mode and len(kept[-1][1]) == 4
        assert kept[0][0] == ("COL-REFLECT" if tick == 0 else modes[0])  # the first measurement of the tick


# ================================================================================ 3. containment


@pytest.mark.parametrize("where", ["write", "hot_write", "snapshot", "call"])
def test_a_failure_applying_one_bricks_ops_ends_that_brick_loudly_and_the_other_runs_on(
    where, honest_alone_poses, capsys
):
    """Our own bug (here a ZeroDivisionError planted where a brick's ops reach the world) ends the brick
    whose ops hit it, with a reason that says it was the simulator's failure; the traceback goes to
    stderr; the other robot's run goes on to its end, as it runs beside a robot that stands still."""
    world = world_with(2)
    attacker = FakeBrick(
        [
            [
                "ops",
                [
                    ["k", 0, "tacho-motor", "motor1", "speed_sp"],
                    ["k", 1, "tacho-motor", "motor1", "position"],
                    ["R", 1],
                    ["q"],
                    ["W", 0, "100"] if where == "write" else ["w", 0, "100"],
                    ["C", 0, "devices", ["tacho-motor", "*", {}]] if where == "call" else ["t", TICK],
                    ["q"],
                ]
                + [["t", TICK * (i + 2)] for i in range(50)],
            ],
        ]
    )
    honest = honest_brick()
    sim = Simulation(world, [(f"r{i}", world.robot, world.starts[i]) for i in range(2)])
    device = sim.robots[0].brick.device("tacho-motor", "motor1")
    calls = {"n": 0}

    def planted(*args):
        calls["n"] += 1
        if where != "snapshot" or calls["n"] > 3:
            raise ZeroDivisionError("planted")
        return "0"

    if where in ("write", "hot_write"):
        device.writers["speed_sp"] = planted
    elif where == "snapshot":
        device.readers["position"] = planted
    else:
        sim.robots[0].brick.list_device_names = planted
    ports = [
        BrickPort(i, sim.robots[i], b.port_channel, sim.trace, []) for i, b in enumerate((attacker, honest))
    ]
    session = Session(sim, ports, 3_000_000, 0.5)
    try:
        session.run()
    finally:
        attacker.close()
        honest.close()
    assert ports[0].gone.startswith("simulator failure:") and "ZeroDivisionError: planted" in ports[0].gone
    assert "Traceback" in capsys.readouterr().err
    assert_honest_finished(ports, sim, honest_alone_poses)
    assert session.world_us == 100 * TICK


JSON_VALUES = [None, True, False, 0, -1, 1, 7, 2**31, 2**70, 10**400, 1.5, -0.0, math.nan, math.inf, "", "x",
               "motor1", "q", "\ud800", "x" * 10_000, [], [0], [[]], {}, {"a": 1}, {"t_us": 5}]  # fmt: skip
KINDS = ["k", "w", "W", "t", "R", "c", "C", "p", "@", "q", "end", "x", "", 5, None, []]


def malformed_ops():
    for kind in KINDS:
        yield [kind]
        for a in JSON_VALUES:
            yield [kind, a]
            for b in JSON_VALUES[::3]:
                yield [kind, a, b]
                yield [kind, 1, a, b]
                yield [kind, 0, "sound", [a, b]]
                yield [kind, 0, "devices", [a, b, {"driver_name": a}]]
                yield [kind, 0, "display", [a]]
                yield [kind, 0, "buttons", [a]]
                yield [kind, 0, a, [b]]
                yield [kind, 1, "tacho-motor", a, b]


def test_no_op_however_malformed_is_taken_for_the_simulators_own_failure():
    """Every op of every kind with every sort of JSON value in every place: the port answers it, or ends
    the brick as a breach of the protocol (or of a budget); never with another exception, which would
    be reported as the simulator's own failure."""
    world = world_with(1)
    sim = Simulation(world, [("r", world.robot, world.starts[0])])
    sent = []
    count = 0
    for op in malformed_ops():
        port = BrickPort(0, sim.robots[0], SimpleNamespace(send=sent.append), sim.trace, [])
        port.time_us = 0
        setup = [
            ["k", 0, "tacho-motor", "motor1", "speed_sp"],
            ["k", 1, "leds", "led0:red:brick-status", "brightness"],
        ]
        try:
            port.accept(["ops", [*setup, op, ["q"]]])
            port.accept(["end", {"t_us": 10**6, "status": "finished"}])
            port.run_ops(0)
        except (ProtocolError, OverBudget):
            pass
        count += 1
        sent.clear()
    assert count > 10_000


# ======================================================================================== 4. hangs

LOOKS_ALIVE = {  # (its clock is at TICK)
    "heartbeat": [["@", TICK]],
    "printed_line": [["p", TICK, "stdout", "still here"]],
    "sound_call": [["c", TICK, "sound", ["set_volume", {"pct": 50}]]],
    "lcd_frame": [["c", TICK, "display", ["00" * 178 * 128]]],
    "answered_call": [["C", TICK, "sound", ["get_volume", {}]], ["q"]],
    "read": [["R", 0], ["q"]],
    "write": [["w", 0, "100"]],
    "checked_write": [["W", 0, "100"], ["q"]],
    "request": [["q"]],
    "debugger_stop": [
        ["C", TICK, "debug", [{"event": "stopped", "file": "p.py", "line": 1}]],
        ["q"],
    ],  # (nobody debugs)
    "new_key": None,  # a new attribute each time
}


def _new_keys():
    for key in range(1, KEYS):
        yield ["ops", [["k", key, "tacho-motor", "motor1", f"attribute{key}"]]]
        yield 0.01


@pytest.mark.parametrize("op", list(LOOKS_ALIVE))
def test_a_brick_whose_clock_stands_still_is_hung_whatever_it_sends(op, honest_alone_poses):
    """Heartbeats, lines, calls, reads, writes, requests and keys that do not move the brick's clock, sent
    every 10 ms for ever, do not keep it alive: it is stopped as hung, and the world goes on for the other."""
    define = ["ops", [["k", 0, "tacho-motor", "motor1", "speed_sp"], ["t", TICK]]]
    alive = _new_keys() if LOOKS_ALIVE[op] is None else forever(["ops", LOOKS_ALIVE[op]])
    session, ports, sim = play(
        [FakeBrick(itertools.chain([define], alive)), honest_brick()], hang_after_s=0.5
    )
    assert ports[0].gone == "hung"
    assert_honest_finished(ports, sim, honest_alone_poses)
    assert session.world_us == 100 * TICK


def test_a_brick_that_waits_for_the_world_or_computes_a_while_is_not_hung(honest_alone_poses):
    """A brick far ahead waits for the world for seconds (not its fault); a slow brick takes most of the
    hang time to compute each tick, and prints without moving its clock meanwhile: neither is hung."""
    slow = []
    for i in range(12):
        slow += [
            0.2,
            ["ops", [["p", i * TICK, "stdout", f"tick {i}"]]],
            0.2,
            ["ops", [["t", (i + 1) * TICK]]],
        ]
    slow.append(["end", {"t_us": 12 * TICK, "status": "finished"}])
    session, ports, sim = play([FakeBrick(slow), honest_brick()], hang_after_s=0.5)
    assert ports[0].gone is None and ports[0].end["status"] == "finished"
    assert_honest_finished(ports, sim, honest_alone_poses)


def test_time_the_simulator_spends_on_one_brick_is_not_held_against_another(honest_alone_poses):
    """While the simulator is busy applying one brick's flood, a slow honest brick's clock cannot be seen
    to move: that time is not held against it.  The flooder is the one stopped."""
    flood = ["ops", [["c", 0, "display", ["00" * 178 * 128]]] * 150]
    slow = []
    for i in range(8):
        slow += [0.3, ["ops", [["t", (i + 1) * TICK]]]]
    slow.append(["end", {"t_us": 8 * TICK, "status": "finished"}])
    session, ports, sim = play(
        [FakeBrick(forever(flood, every_s=0)), FakeBrick(slow), honest_brick()], hang_after_s=0.5
    )
    assert ports[0].gone in ("hung",) or ports[0].gone.startswith("budget"), ports[0].gone
    assert ports[1].gone is None and ports[1].end["status"] == "finished"
    assert ports[2].gone is None and ports[2].end["status"] == "finished"


HUNG_ATTACKS = {
    "heartbeats": """\
        t = max(now(), link.declared)
        while True:
            send(["@", t])
            pause()
        """,
    "printed_lines": """\
        t = max(now(), link.declared)
        while True:
            link.output(t, "stdout", "alive")
            pause()
        """,
    "calls": """\
        while True:
            link.call("sound", "get_volume")
            link.call("sound", "get_volume")  # (a look at the buttons costs the brick 1 ms, as on an EV3)
            pause()
        """,
    "reads_and_writes": """\
        key = link._key("tacho-motor", "motor1", "speed_sp")
        while True:
            ask(["W", key, "100"], ["R", key])
            send(["w", key, "200"])
            pause()
        """,
}


@pytest.mark.parametrize("attack", list(HUNG_ATTACKS))
def test_a_real_brick_that_looks_alive_without_its_clock_moving_is_hung(attack, alone, tmp_path):
    program = PRELUDE + "time.sleep(0.1)\n" + textwrap.dedent(HUNG_ATTACKS[attack])
    ran = run_cli(tmp_path, program, HONEST, hang_after_s=1.0)
    assert_contained(
        ran, alone, "stopped: the program ran for a while without using the robot or the clock", tmp_path
    )


# ============================================================================= serve, with joins


class Served:
    """An `ev3sim2d serve` process in line-shared, measured, and the port it listens on."""

    def __init__(self, tmp_path: Path, *args: str) -> None:
        self.err_path = tmp_path / "serve.err"
        self.process = subprocess.Popen(
            [sys.executable, "-c", MEASURED, "serve", "--port", "0", "--maze", "line-shared", *args],
            stdout=subprocess.DEVNULL,
            stderr=open(self.err_path, "w"),
            cwd=tmp_path,
            env=_env(),
        )
        try:
            port = int(self.wait_for(r"serving .* on \S+:(\d+)").group(1))
            self.address = f"127.0.0.1:{port}"
        except BaseException:
            self.stop()
            raise

    def log(self) -> str:
        return self.err_path.read_text()

    def wait_for(self, pattern: str, timeout_s: float = 60.0) -> re.Match:
        end = time.monotonic() + timeout_s
        while time.monotonic() < end:
            found = re.search(pattern, self.log())
            if found:
                return found
            if self.process.poll() is not None:
                break
            time.sleep(0.02)
        raise AssertionError(f"no {pattern!r} in serve's log:\n{self.log()}")

    def finish(self, timeout_s: float = 120.0) -> int:
        return self.process.wait(timeout=timeout_s)

    def peak_mb(self) -> float:
        return _peak_mb(self.log())

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()


def _program(tmp_path: Path, name: str, source: str) -> Path:
    path = tmp_path / name
    path.write_text(textwrap.dedent(source))
    return path


def _join(address: str, program: Path, flag: str, robot: str, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "join", address, str(program), flag, robot],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd, env=_env(), start_new_session=True,
    )  # fmt: skip


class FakeJoin:
    """A joining computer played by hand: the join, the hello, then whatever the test sends."""

    def __init__(self, address: str, robot: int) -> None:
        host, port = address.rsplit(":", 1)
        self.sock = socket.create_connection((host, int(port)), timeout=30)
        self.buffer = b""
        self.sock.sendall(encode(join_message(None, robot, "mallory", "mallory.py", "/nowhere/mallory.py")))
        assert self.receive()[0] == "seat"
        self.sock.sendall(encode(["hello", {"protocol": PROTOCOL, "sandbox": {}}]))

    def receive(self) -> list | None:
        while b"\n" not in self.buffer:
            data = self.sock.recv(65536)
            if not data:
                return None
            self.buffer += data
        line, self.buffer = self.buffer.split(b"\n", 1)
        return decode(line)

    def flood(self, messages) -> None:
        """Send these (a number: sleep that long) from a thread until the world closes the connection;
        and read what it sends."""

        def send():
            try:
                for message in messages:
                    if isinstance(message, (int, float)):
                        time.sleep(message)
                    else:
                        self.sock.sendall(message if isinstance(message, bytes) else encode(message))
            except OSError:
                pass

        def read():
            try:
                while self.sock.recv(65536):
                    pass
            except OSError:
                pass

        threading.Thread(target=send, daemon=True).start()
        threading.Thread(target=read, daemon=True).start()

    def close(self) -> None:
        self.sock.close()


def timed(make, every_s: float = 0.01):
    """Messages made for a clock that moves on 1 ms each time (so the brick is never hung), every_s apart."""
    t_us = 0
    while True:
        t_us += 1000
        yield make(t_us)
        yield every_s


JOIN_ATTACKS = {
    "heartbeats": (
        forever(["ops", [["@", 0]]], every_s=0.005),
        "hung",
        "the program on the other computer ran",
    ),
    "printed_bytes": (
        timed(lambda t: ["ops", [["p", t, "stdout", "x" * 1_000_000]]]),
        "crashed",
        "budget: the program printed more than 2 MB",
    ),
    "notes": (
        timed(
            lambda t: [
                "ops",
                [["c", t, "sound", ["beep", {"notes": [{"length_ms": 1, "notes": [{}] * 100}] * 200}]]],
            ]
        ),
        "crashed",
        "budget: the program's beeps held more than",
    ),
    "lcd": (
        timed(
            lambda t: ["ops", [["c", t * 50, "display", [(t.to_bytes(4, "big") + bytes(22780)).hex()]]]], 0
        ),
        "crashed",
        "budget: the program drew more than",
    ),
    "deep_json": (
        [b'["ops",' + b"[" * 100_000 + b"]" * 100_000 + b"]\n", 30.0],
        "crashed",
        "protocol: not a JSON message",
    ),
}
EXIT_STATUS = {"crashed": 1, "hung": 3}


@pytest.mark.parametrize("attack", list(JOIN_ATTACKS))
def test_a_joined_attacker_ends_alone_and_serve_runs_on(attack, tmp_path):
    """A joined computer's brick played by hand floods the world: its robot is dropped with the reason,
    the honest student's run beside it goes on to its end, serve ends normally and stays small."""
    messages, status, reason = JOIN_ATTACKS[attack]
    served = Served(
        tmp_path, "--robots", "2", "--time", "30", "--hang-after", "1", "--summary", "served.json"
    )
    mallory = None
    try:
        mallory = FakeJoin(served.address, 1)
        honest = _join(served.address, _program(tmp_path, "honest.py", HONEST), "--robot", "2", tmp_path)
        assert mallory.receive()[0] == "snap"
        mallory.flood(messages)
        out, err = honest.communicate(timeout=120)
        assert served.finish() == EXIT_STATUS[status], served.log()
    finally:
        if mallory is not None:
            mallory.close()
        served.stop()
    assert honest.returncode == 0 and "] done" in out, err
    assert "Traceback" not in served.log(), served.log()
    summary = json.loads((tmp_path / "served.json").read_text())
    assert summary["status"] == status and reason in summary["reason"], summary["reason"]
    assert re.search(r"robot2 \(honest[^)]*\): finished at 3\.26 s", served.log()), served.log()
    assert served.peak_mb() < MEMORY_CEILING_MB


# ==================================================================================== 5. rendering


def a_hand_made_trace_past_every_sound_budget() -> Trace:
    """A trace as an older simulator (or a hand) could have left it, 10 s of two robots: sounds far past
    every budget (hours of tones, thousands of speeches), and numbers no brick port would have kept."""
    world = world_with(2)
    sim = Simulation(world, [(f"r{i}", world.robot, world.starts[i]) for i in range(2)])
    for tick in range(1, 1001):
        sim.tick(tick * TICK)
    trace = sim.finish()
    long = [{"frequency": 200 + i, "length_ms": 60_000, "repeats": 100, "delay_ms": 0} for i in range(50)]
    short = [{"frequency": 2000 + i, "length_ms": 1, "repeats": 100, "delay_ms": 0} for i in range(50)]
    garbage = [
        {"frequency": "loud", "length_ms": math.nan, "repeats": 10**9},
        {"repeats": 10**400},
        "note",
        None,
    ]
    for i in range(4_000):
        robot, t = i % 2, i * 0.0025
        trace.add_event(t, robot, "sound", {"kind": "beep", "notes": short + long + garbage})
        trace.add_event(t, robot, "sound", {"kind": "speak", "text": "w" * 1000, "duration": 0.01})
        trace.add_event(t, robot, "sound", {"kind": "play_file", "wav_file": "/f" * 1000, "duration": 1e9})
    trace.add_event(0.5, 7, "sound", {"kind": "beep", "notes": long})  # a robot the run does not have
    trace.add_event(math.inf, 0, "sound", {"kind": "beep", "notes": long})
    trace.add_event("soon", 0, "sound", {"kind": "beep", "notes": "all of them"})
    trace.result = {"status": "finished", "sim_time_s": 10.0}
    return trace


def test_a_trace_with_sounds_past_every_budget_plays_within_them_in_seconds(tmp_path):
    """Sounds beyond the budgets (hours of tones, a billion repeats, hour-long speeches, nonsense), in a
    trace saved and loaded back as any .npz: the video plays each robot's budget's worth, in seconds."""
    path = tmp_path / "old.npz"
    a_hand_made_trace_past_every_sound_budget().save(path)
    trace = Trace.load(path)
    started = time.perf_counter()
    spans = sound_spans(trace)
    for robot in (0, 1):
        tones = [s for s in spans if s.robot == robot and s.kind == "tone"]
        assert 0 < len(tones) <= SOUND_NOTES
        assert sum(s.end_s - s.start_s for s in spans if s.robot == robot) <= SOUND_SECONDS + 1e-6
    assert len([s for s in spans if s.kind != "tone"]) <= 2 * EVENTS
    assert sum(s.kind == "tone" for s in spans) == 2 * SOUND_NOTES
    timeline = Timeline(trace)
    assert all(timeline.sounds_at(robot, t) for robot in (0, 1) for t in np.arange(0.01, 5.0, 0.01))
    assert sound_track(spans, 10.0) is not None
    assert time.perf_counter() - started < RENDER_CEILING_S
    assert render_s(trace, tmp_path / "old.mp4") < RENDER_CEILING_S


def test_grade_videos_of_a_budgets_worth_of_sound_are_made_quickly(tmp_path):
    """`ev3sim2d grade --videos` of a program that plays every note and second of sound its budgets allow,
    all at once (ten beeps that do not wait), then fails the lesson: the video of its run is made quickly.
    (A run that goes past a budget ends as crashed, which a grader does not judge, nor keep a video of.)"""
    lesson = write_lesson(tmp_path / "lesson", time_s=5)
    notes = SOUND_NOTES // 10 // 100
    write_program(
        tmp_path / "class",
        "mallory.py",
        PRELUDE
        + textwrap.dedent(
            f"""\
            length_ms = {SOUND_SECONDS} * 1000 / {SOUND_NOTES}
            notes = [{{"frequency": 300 + 50 * i, "length_ms": length_ms, "repeats": 100}} for i in range({notes})]
            for _ in range(10):
                link.call("sound", "beep", {{"notes": notes, "duration": 60.0, "play_type": 1}})
            time.sleep(1)
            print("played")
            """
        ),
    )
    started = time.perf_counter()
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(tmp_path / "class"), "--videos",
         str(tmp_path / "videos")],
        capture_output=True, text=True, cwd=ROOT, timeout=300,
    )  # fmt: skip
    wall = time.perf_counter() - started
    assert done.returncode == 1, done.stderr
    assert "(crashed)" not in done.stdout + done.stderr, done.stdout
    videos = list((tmp_path / "videos").rglob("*.mp4"))
    assert [v.relative_to(tmp_path / "videos").as_posix() for v in videos] == ["mallory/room.mp4"]
    assert wall < 30, f"grading and its video took {wall:.1f} s"
