"""One run: programs drive their robots in a world until they end, the time limit, or a hang.

Each program runs in a brick process of its own (ev3sim2d/brick/), sandboxed,
on a robot of its own (program i starts at the world's start pose i, as the
robot that start names, the world's robot, or the robot the caller gives); this
process holds the world, steps it in lockstep with the bricks (session.py) and
records the trace.  Nothing a program does reaches this process except through
the protocol.  Whatever happens, the result holds the trace up to that moment,
and no process of the run is left behind.
"""

from __future__ import annotations

import gc
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from .brick_port import BrickPort
from .brick_process import BrickLimits, BrickProcess, shim_root, site_packages, start_brick
from .program import Program, ProgramError
from .protocol import PROTOCOL, ProtocolError
from .session import Session
from .simulation import Simulation, StartBlocked
from .trace import OutputLine, Trace
from .world.robot_spec import RobotSpec
from .world.world import World

_real_perf_counter = time.perf_counter
_monotonic = time.monotonic
START_TIMEOUT_S = 60.0  # a brick must be ready (interpreter, shim, sandbox) within this much real time
LIMIT_SIGNALS = {"SIGXCPU": "cpu", "SIGXFSZ": "output"}
CRASH_SIGNALS = {
    "SIGSEGV": "a segmentation fault",
    "SIGABRT": "an abort",
    "SIGBUS": "a bus error",
    "SIGILL": "an illegal instruction",
    "SIGFPE": "a floating point exception",
}


@dataclass
class RunResult:
    """How a run ended, and what happened in it."""

    status: str  # finished, error, time_limit, hung, interrupted, crashed
    reason: str  # one line for the terminal
    sim_time_s: float
    wall_time_s: float
    trace: Trace | None
    error: dict | None = None  # type, message, file, line, t_s, traceback
    limit: str | None = None  # the brick's limit it ran into: cpu, memory, output
    sandbox: list[dict] = field(default_factory=list)  # per brick: the isolation it got, layer by layer

    @property
    def ok(self) -> bool:
        return self.status in ("finished", "time_limit")


def _describe_devices(robot) -> str:
    parts = [f"{p} {m.kind} motor" for p, m in robot.motors.items()]
    parts += [f"{p} {s.spec.kind} sensor" for p, s in robot.sensors.items()]
    return ", ".join(parts)


def robot_specs(
    world: World, count: int, robot: RobotSpec | Sequence[RobotSpec | None] | None = None
) -> list[RobotSpec]:
    """The robot of each of `count` programs in the world.

    `robot` is one spec for every program, or one per program (None: not given); a robot not given is
    the one the program's start pose names, else the world's.
    """
    if robot is None or isinstance(robot, RobotSpec):
        given: list[RobotSpec | None] = [robot] * count
    else:
        given = list(robot)
        if len(given) == 1:
            given *= count
        elif len(given) != count:
            raise ValueError(
                f"{len(given)} robots for {count} programs; give one robot for every program, "
                "or one per program in the programs' order"
            )
    return [spec if spec is not None else world.start_robot(i) for i, spec in enumerate(given)]


def run_programs(
    programs: list[str | Path],
    world: World,
    robot: RobotSpec | Sequence[RobotSpec | None] | None = None,
    time_limit_s: float | None = 60.0,
    seed: int = 0,
    hang_after_s: float = 5.0,
    echo=None,
    presses: list | None = None,
    readable: list[list[Path]] | None = None,
    limits: BrickLimits | None = None,
    sandbox: bool = True,
    scratch_in: Path | None = None,
    program_seed: int | None = None,
    spin: bool = True,
    zygote=None,
) -> RunResult:
    """Run each program on its own robot in the world; see the module docstring.

    robot: the robot of every program, or a list with one per program (None in it, or no robot: the
    robot the program's start pose names, else the world's robot).
    presses: scripted button presses (ButtonPress), added to the world file's.
    readable: per program, what its brick may read besides Python itself (default: the program's folder).
    limits: CPU time, memory, file sizes and processes of each brick.
    sandbox: False only for measuring what the sandbox costs; a program is never graded without one.
    scratch_in: where each brick's scratch folder is made (default: the system's temporary folder).
    program_seed: the seed of the programs' `random` (default: seed, which also seeds sensor noise).
    spin: whether simulator and bricks may spin while they wait for each other (False when other runs
    share the cores, as in a class run with --jobs 2).
    zygote: a BrickZygote to fork the bricks from (a class run's), instead of starting each afresh.
    Nothing tells a brick which world it is in, or when the run will be stopped (the time limit is the
    simulator's): a program learns of the world only by its sensors.
    """
    loaded = [Program(p) for p in programs]  # ProgramError: the caller reports it
    if len(loaded) > len(world.starts):
        raise ProgramError(
            f"{len(loaded)} programs but the world '{world.name}' has {len(world.starts)} start pose(s); "
            f"add starts to the world file or run fewer programs"
        )
    specs = robot_specs(world, len(loaded), robot)
    names = ["robot"] if len(loaded) == 1 else [f"robot{i + 1}" for i in range(len(loaded))]
    sim = Simulation(world, [(names[i], specs[i], world.starts[i]) for i in range(len(loaded))], seed=seed)
    limit_us = None if time_limit_s is None else int(round(time_limit_s * 1e6))
    presses = sorted([*world.buttons, *(presses or ())], key=lambda p: p.at_s)
    sim.trace.world["buttons"] = [[p.button, p.at_s, p.hold_s] for p in presses]
    limits = limits or BrickLimits()
    bricks: list[BrickProcess] = []
    ports: list[BrickPort] = []
    printed: list = []
    session = None
    wall = 0.0
    try:
        for i, program in enumerate(loaded):
            path = program.path.resolve()
            may_read = readable[i] if readable else [path.parent]
            brick, read_paths = start_brick(list(may_read), scratch_in=scratch_in, spin=spin, zygote=zygote)
            bricks.append(brick)
            config = {
                "protocol": PROTOCOL,
                "robot": names[i],
                "tick_us": sim.tick_us,
                "seed": seed if program_seed is None else program_seed,
                "program": str(path),
                "program_dirs": [str(path.parent)],
                "shim_root": str(shim_root()),
                "site_packages": site_packages(),
                "sandbox": {
                    "read_paths": read_paths,
                    "write_paths": [str(brick.scratch)],
                    "cpu_s": limits.cpu_s,
                    "memory_mb": limits.memory_mb,
                    "file_mb": limits.file_mb,
                    "processes": limits.processes,
                }
                if sandbox
                else None,
            }
            brick.channel.send(["welcome", config])
            ports.append(BrickPort(i, sim.robots[i], brick.channel, sim.trace, presses, printed))
        for port in ports:
            _await_hello(port)
        session = Session(sim, ports, limit_us, hang_after_s, printed, echo, spin=spin)
        wall_start = _real_perf_counter()
        session.run()
        wall = _real_perf_counter() - wall_start
    except KeyboardInterrupt:
        for port in ports:
            port.gone = port.gone or "interrupted"
        session = session or Session(sim, ports, limit_us, hang_after_s)
        session.interrupted = True
    finally:
        for i, brick in enumerate(bricks):
            gone = ports[i].gone if i < len(ports) else "start"
            ending = gone is None or gone.startswith(("gone", "start"))
            brick.stop(patience_s=2.0 if ending else 0.0)
    result = _result(sim, loaded, ports, bricks, wall, session)
    del sim, ports, session
    gc.collect()  # free the pymunk world now: left to interpreter exit, its teardown complains
    return result


def _await_hello(port: BrickPort) -> None:
    """The brick is up (interpreter, shim, sandbox) and says what isolation it got."""
    try:
        message = port.channel.receive(timeout_s=START_TIMEOUT_S)
    except ProtocolError as err:
        port.gone = f"start: {err}"
        return
    if message is None:
        port.gone = f"start: the brick was not ready within {START_TIMEOUT_S:g} s"
    elif message[0] == "hello" and len(message) == 2 and isinstance(message[1], dict):
        port.hello = message[1]
    elif message[0] == "end" and len(message) == 2 and isinstance(message[1], dict):
        port.end = message[1]  # it could not even start the program (it says why)
    else:
        port.gone = "start: the brick did not greet"


def _program_error(port: BrickPort, program: Program) -> dict | None:
    """The program's error as the brick reported it, checked and with the file named as the user named it."""
    how = port.end or {}
    error = how.get("error")
    if how.get("status") != "error" or not isinstance(error, dict):
        return None
    shown, real = str(program.path), str(program.path.resolve())

    def text(key: str, limit: int = 20_000) -> str:
        value = error.get(key)
        return str(value)[:limit].replace(real, shown) if value is not None else ""

    line = error.get("line")
    report = {
        "type": text("type", 200) or "Exception",
        "message": text("message", 2000),
        "file": text("file", 1000) or None,
        "line": line if type(line) is int else None,
        "t_s": port.time_us / 1e6,
        "traceback": text("traceback"),
        "hint": None,
    }
    if report["type"] == "DeviceNotFound":
        report["hint"] = f"this robot has: {_describe_devices(port.robot)}"
    return report


def _crash(port: BrickPort, brick: BrickProcess) -> tuple[str, str | None]:
    """Why a brick ended without saying so: a limit it ran into, or how its process died."""
    name = brick.ended_by_signal()
    console = brick.console_text
    if name in LIMIT_SIGNALS:
        return LIMIT_SIGNALS[name], LIMIT_SIGNALS[name]
    if "MemoryError" in console:
        return "memory", "memory"
    if name in CRASH_SIGNALS:
        return f"the Python interpreter running the program crashed ({CRASH_SIGNALS[name]}, {name})", None
    if name is not None:
        return f"the program's process was killed by {name}", None
    last = console.splitlines()[-1] if console else "no message"
    return f"the program's process ended without a word (exit status {brick.popen.returncode}: {last})", None


def _result(sim, programs, ports, bricks, wall, session) -> RunResult:
    t = session.world_us / 1e6 if session is not None else 0.0
    error = None
    status = None
    reason = None
    limit = None
    for port, program, brick in zip(ports, programs, bricks, strict=False):
        found = _program_error(port, program)
        if found is not None and error is None:
            error = found
            if len(programs) > 1:
                error["robot"] = port.robot.name
        if port.gone == "hung" and status is None:
            status = "hung"
            reason = (
                f"stopped: the program ran for a while without using the robot or the clock "
                f"(a loop with no sensor read, motor command or sleep?) at {t:.2f} s"
            )
        elif port.gone == "interrupted" and status is None:
            status, reason = "interrupted", f"interrupted at {t:.2f} s"
        elif port.gone is not None and port.gone != "time limit" and status is None:
            what, limit = (
                _crash(port, brick) if port.gone.startswith(("gone", "start")) else (port.gone, None)
            )
            if limit == "cpu":
                what = "the program used more CPU time than it may"
            elif limit == "output":
                what = "the program wrote files larger than it may"
            elif limit == "memory":
                what = "the program ran out of memory"
            status, reason = "crashed", f"{what} (at {t:.2f} s)"
    ends = [(port.end or {}).get("status") for port in ports]
    if status is None and error is not None:
        status = "error"
        where = f"{error['file']}, line {error['line']}, " if error["line"] else ""
        reason = f"{error['type']}: {error['message']} ({where}at {t:.2f} s)"
    elif status is None and "deadlock" in ends:
        status = "hung"
        reason = f"stopped: every thread of the program is waiting for another (a deadlock) at {t:.2f} s"
    elif status is None and "time_limit" in ends:
        status, reason = "time_limit", f"ran until the time limit of {t:.2f} s"
    elif status is None:
        status, reason = "finished", f"finished at {t:.2f} s"
    if error is not None and error["type"] == "MemoryError":
        limit = "memory"
    trace = sim.finish()
    trace.output.sort(key=lambda line: (line.t_s, line.robot))
    trace.events.sort(key=lambda e: (e[0], e[1]))
    dropped = sum(port.dropped_lines for port in ports)
    trace.result = {
        "status": status,
        "reason": reason,
        "sim_time_s": t,
        "error_type": error["type"] if error else None,
        "error": error,
        "dropped_output_lines": dropped,
        "dropped_events": sum(port.dropped_events for port in ports),
        "limit": limit,
    }
    sandbox = [dict((port.hello or {}).get("sandbox") or {}) for port in ports]
    return RunResult(status, reason, t, wall, trace, error, limit, sandbox)


def echo_line(stream, robots: int = 1) -> Callable[[OutputLine], None]:
    """An echo for run_programs that prints each line with its virtual time (and robot, if several)."""

    def echo(line: OutputLine) -> None:
        who = f" robot{line.robot + 1}" if robots > 1 else ""
        stream.write(f"[{line.t_s:8.3f} s{who}] {line.text}\n")

    return echo


__all__ = ["run_programs", "robot_specs", "RunResult", "ProgramError", "StartBlocked", "echo_line"]
