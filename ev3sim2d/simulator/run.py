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
import os
import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..devices.motor import RUNNING
from ..protocol import ProtocolError
from ..results.trace import OutputLine, Trace
from ..world.pose import Pose
from ..world.robot_spec import RobotSpec
from ..world.world import World
from .brick_port import BrickPort
from .bricks import BrickLimits, BrickProcess, brick_welcome, start_brick
from .cores import RunCores
from .program import Program, ProgramError
from .session import Session
from .simulation import Simulation, StartBlocked

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
    robots: list[dict] = field(default_factory=list)  # per robot: its name, how its program ended and why
    notes: list[str] = field(default_factory=list)  # what the user should know that is not an error

    @property
    def ok(self) -> bool:
        return self.status in ("finished", "time_limit")


EV3_PORTS = {*(f"INPUT_{n}" for n in "1234"), *(f"OUTPUT_{letter}" for letter in "ABCD")}


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


def robot_names(count: int) -> list[str]:
    """The robots' names in the trace: `robot` alone, else robot1, robot2, ..."""
    return ["robot"] if count == 1 else [f"robot{i + 1}" for i in range(count)]


def new_simulation(
    world: World,
    count: int,
    robot: RobotSpec | Sequence[RobotSpec | None] | None,
    seed: int,
    presses: list | None,
    starts: Sequence[Pose] | None = None,
) -> tuple[Simulation, list]:
    """The world with `count` robots at its first starts (or at `starts`), and the run's scripted button
    presses."""
    if count > len(world.starts):
        raise ProgramError(
            f"{count} programs but the world '{world.name}' has {len(world.starts)} start pose(s); "
            f"add starts to the world file or run fewer programs"
        )
    specs = robot_specs(world, count, robot)
    names = robot_names(count)
    starts = list(starts or world.starts)
    sim = Simulation(world, [(names[i], specs[i], starts[i]) for i in range(count)], seed=seed)
    presses = sorted([*world.buttons, *(presses or ())], key=lambda p: p.at_s)
    sim.trace.world["buttons"] = [[p.button, p.at_s, p.hold_s] for p in presses]
    return sim, presses


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
    arguments: Sequence[str] = (),
    debug: str | None = None,
    debugger=None,
    keep_written: bool = False,
    place: bool = True,
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
    place: whether a run of several bricks may give the simulator a core of its own and the bricks the
    others (simulator/cores.py): not when other runs share the machine (a class graded in parallel).
    zygote: a BrickZygote to fork the bricks from (a class run's), instead of starting each afresh.
    arguments: every program's command line after its name (its sys.argv[1:]).
    debug: what breakpoint() does in the programs (None: nothing, as in grading; "breakpoints": it stops
    in the brick's debugger; "start": each program stops at its first line too), and debugger the front
    end a stopped program asks: debugger(robot index, shown, real, event) -> command, where shown is the
    program as the caller named it and real its path as its brick knows it (brick/debugger.py).
    Each brick works in a copy of its program's folder (simulator/working_folder.py); keep_written: the
    files a program made beside itself are kept in its folder afterwards (for the one who runs a program
    of their own: never a grader's class folder).
    Nothing tells a brick which world it is in, or when the run will be stopped (the time limit is the
    simulator's): a program learns of the world only by its sensors.
    """
    loaded = [Program(p) for p in programs]  # ProgramError: the caller reports it
    sim, presses = new_simulation(world, len(loaded), robot, seed, presses)
    names = robot_names(len(loaded))
    limit_us = None if time_limit_s is None else int(round(time_limit_s * 1e6))
    limits = limits or BrickLimits()
    bricks: list[BrickProcess] = []
    ports: list[BrickPort] = []
    printed: list = []
    session = None
    wall = 0.0
    cores = RunCores(len(loaded), spin, place)
    try:
        for i, program in enumerate(loaded):
            path = program.path.resolve()
            may_read = readable[i] if readable else [path.parent]
            brick, read_paths = start_brick(
                list(may_read), scratch_in=scratch_in, spin=spin, zygote=zygote, limits=limits, program=path
            )
            cores.brick_started(i, brick.popen.pid)
            brick.keep_written = keep_written
            bricks.append(brick)
            brick_seed = seed if program_seed is None else program_seed
            brick.channel.send(
                brick_welcome(
                    brick,
                    read_paths,
                    path,
                    names[i],
                    sim.tick_us,
                    brick_seed,
                    limits,
                    sandbox,
                    arguments,
                    debug,
                )
            )
            ports.append(BrickPort(i, sim.robots[i], brick.channel, sim.trace, presses, printed))
            if debugger is not None:
                shown, real = str(program.path), ran_as(path, brick)
                ports[-1].debugger = lambda event, i=i, shown=shown, real=real: debugger(
                    i, shown, real, event
                )
        for port in ports:
            await_hello(port)
        cores.start()
        session, wall = play(sim, ports, limit_us, hang_after_s, printed, echo, spin)
    except KeyboardInterrupt:  # while the bricks start
        for port in ports:
            port.gone = port.gone or "interrupted"
        session = Session(sim, ports, limit_us, hang_after_s)
        session.interrupted = True
    finally:
        cores.end()
        for i, brick in enumerate(bricks):
            gone = ports[i].gone if i < len(ports) else "start"
            ending = gone is None or gone.startswith(("gone", "start"))
            brick.stop(patience_s=2.0 if ending else 0.0)
    shown = [(str(p.path), ran_as(p.path.resolve(), brick)) for p, brick in zip(loaded, bricks, strict=False)]
    result = run_result(sim, shown, ports, bricks, wall, session)
    result.notes += [
        f"{p.path}: {b.working.note}"
        for p, b in zip(loaded, bricks, strict=False)
        if b.working and b.working.note
    ]
    for p, b in zip(loaded, bricks, strict=False):
        kept, not_kept = b.kept
        if kept:
            result.notes.append(f"{p.path}: kept what it wrote beside itself: {', '.join(kept)}")
        if not_kept:
            result.notes.append(f"{p.path}: did not keep what it wrote: {'; '.join(not_kept)}")
    del sim, ports, session
    gc.collect()  # free the pymunk world now: left to interpreter exit, its teardown complains
    return result


def ran_as(path: Path, brick: BrickProcess | None) -> str:
    """The program's path as its brick knew it: its copy in the folder the brick worked in."""
    return str(path if brick is None or brick.working is None else brick.working.program)


def play(
    sim: Simulation,
    ports: list[BrickPort],
    limit_us: int | None,
    hang_after_s: float,
    printed: list,
    echo,
    spin: bool = True,
) -> tuple[Session, float]:
    """The session of bricks that have all said hello, to its end; it and its wall time."""
    session = Session(sim, ports, limit_us, hang_after_s, printed, echo, spin=spin)
    wall_start = _real_perf_counter()
    try:
        session.run()
    except KeyboardInterrupt:  # (session.run handles one during the run; this is one at its very end)
        for port in ports:
            port.gone = port.gone or "interrupted"
        session.interrupted = True
    return session, _real_perf_counter() - wall_start


def await_hello(port: BrickPort, timeout_s: float = START_TIMEOUT_S) -> None:
    """The brick is up (interpreter, shim, sandbox) and says what isolation it got."""
    try:
        message = port.channel.receive(timeout_s=timeout_s)
    except ProtocolError as err:
        port.gone = f"start: {err}"
        return
    if message is None:
        port.gone = f"start: the brick was not ready within {timeout_s:g} s"
    else:
        take_hello(port, message)


def take_hello(port: BrickPort, message: list) -> None:
    """A brick's first message: hello, or the end of a program it could not even start."""
    if message[0] == "hello" and len(message) == 2 and isinstance(message[1], dict):
        port.hello = message[1]
    elif message[0] == "end" and len(message) == 2 and isinstance(message[1], dict):
        port.end = message[1]  # it could not even start the program (it says why)
    else:
        port.gone = "start: the brick did not greet"


def program_error(port: BrickPort, shown: str, real: str) -> dict | None:
    """The program's error as the brick reported it, checked and with the file named as the user named it
    (shown; real: its path as the brick knows it)."""
    how = port.end or {}
    error = how.get("error")
    if how.get("status") != "error" or not isinstance(error, dict):
        return None

    real_dir = os.path.join(os.path.dirname(real), "")  # its folder: the modules beside it, as named too
    shown_dir = os.path.join(os.path.dirname(shown), "") if os.path.dirname(shown) else ""

    def text(key: str, limit: int = 20_000) -> str:
        value = error.get(key)
        return (
            str(value)[:limit].replace(real, shown).replace(real_dir, shown_dir) if value is not None else ""
        )

    line = error.get("line")
    report = {
        "type": text("type", 200) or "Exception",
        "message": text("message", 2000),
        "file": text("file", 1000) or None,
        "line": line if type(line) is int else None,
        "t_s": port.time_us / 1e6,
        "traceback": text("traceback"),
        "hint": None,
        "compiling": error.get("compiling") is True,  # the brick could not compile the program
    }
    if report["type"] == "DeviceNotFound":
        report["hint"] = f"this robot has: {_describe_devices(port.robot)}"
    elif report["type"] in ("ImportError", "NameError", "AttributeError") and _no_such_port(
        report["message"]
    ):
        report["hint"] = (
            "an EV3 has four input ports for sensors, INPUT_1 to INPUT_4, and four output ports for motors, "
            f"OUTPUT_A to OUTPUT_D; this robot has: {_describe_devices(port.robot)}"
        )
    return report


def _no_such_port(message: str) -> bool:
    """Whether the message names a port an EV3 does not have (INPUT_5, OUTPUT_E, INPUT_A)."""
    return any(name not in EV3_PORTS for name in re.findall(r"'((?:INPUT|OUTPUT)_[A-Za-z0-9]+)'", message))


def start_failure(result: RunResult) -> str | None:
    """Why a program could not even start, as its brick found when it compiled it (a syntax error, a
    file Python cannot read as text, a source too deep to parse): its file and line, the source line and a
    caret, as Python shows them; None when every program started.  (Only a brick compiles a program:
    a student's source is never parsed in this process.)"""
    error = result.error
    if not error or not error.get("compiling"):
        return None
    where = (
        f"{error['file']}, line {error['line']}"
        if error.get("file") and error.get("line")
        else error.get("file")
    )
    lines = [line for line in (error.get("traceback") or "").splitlines() if line.strip()]
    shown = [line for line in lines[1:-1] if not line.lstrip().startswith(("File ", "Traceback"))]
    message = f"{error['type']}: {error['message']}" if error["type"] != "SyntaxError" else error["message"]
    return "\n".join([f"{where or 'the program'}: {message}", *shown])


def _crash(port: BrickPort, brick: BrickProcess | None) -> tuple[str, str | None]:
    """Why a brick ended without saying so: a limit it ran into, or how its process died (brick None:
    a brick on another computer, whose process this one never sees)."""
    if brick is None:
        why = port.gone.split(": ", 1)[-1] if port.gone else "no word"
        return f"the connection to the program's computer was lost ({why})", None
    name = brick.ended_by_signal()
    console = brick.console_text
    if name in LIMIT_SIGNALS:
        return LIMIT_SIGNALS[name], LIMIT_SIGNALS[name]
    limit = brick.limit_at_end()
    if limit is not None:
        return limit, limit
    if "MemoryError" in console:
        return "memory", "memory"
    if name in CRASH_SIGNALS:
        return f"the Python interpreter running the program crashed ({CRASH_SIGNALS[name]}, {name})", None
    if name is not None:
        return f"the program's process was killed by {name}", None
    last = console.splitlines()[-1] if console else "no message"
    return f"the program's process ended without a word (exit status {brick.popen.returncode}: {last})", None


LIMIT_WHAT = {
    "cpu": "the program used more CPU time than it may",
    "output": "the program wrote files larger than it may",
    "memory": "the program ran out of memory",
}


def shown_file(file: str, shown: str, real: str) -> str:
    """A file of the program's, as its brick names it, named as the user named the program (shown; real:
    the program's path as its brick knows it): the program itself, or a file beside it."""
    real_dir = os.path.join(os.path.dirname(real), "")
    shown_dir = os.path.join(os.path.dirname(shown), "") if os.path.dirname(shown) else ""
    return file.replace(real, shown).replace(real_dir, shown_dir)


def shown_places(threads: list | None, shown: str, real: str) -> list[dict]:
    """Where a stopped program's threads were, as its brick said (Session.where): {thread, file, line} each,
    the file named as the user named it (shown_file)."""
    return [
        {"thread": name, "file": shown_file(file, shown, real), "line": line}
        for name, file, line in threads or []
    ]


def where_text(places: list[dict]) -> str:
    """' (it was at prog.py, line 7)', or one place per thread; '' when the brick said nothing."""
    if len(places) == 1:
        return f" (it was at {places[0]['file']}, line {places[0]['line']})"
    if not places:
        return ""
    return (
        " (its threads were: "
        + "; ".join(f"{p['thread']} at {p['file']}, line {p['line']}" for p in places)
        + ")"
    )


def _robot_end(
    port: BrickPort, error: dict | None, brick: BrickProcess | None, t: float, where: str = ""
) -> dict:
    """How one robot's brick ended: status, reason (as for a whole run), and the limit it ran into; where:
    where_text of its threads, for a run stopped at the time limit or as hung.

    `early` marks an end that decides the whole run's status before any program's error (a hang, an
    interruption, a crash)."""
    end = port.end or {}
    if port.gone == "hung":
        what = "the program ran" if brick is not None else "the program on the other computer ran"
        reason = (
            f"stopped: {what} for a while without using the robot or the clock (waiting on something "
            f"outside the simulation, or inside one long call of compiled code?) at {t:.2f} s{where}"
        )
        return {"status": "hung", "reason": reason, "limit": None, "early": True}
    if port.gone == "interrupted":
        return {"status": "interrupted", "reason": f"interrupted at {t:.2f} s", "limit": None, "early": True}
    if port.gone is not None and port.gone != "time limit":
        what, limit = _crash(port, brick) if port.gone.startswith(("gone", "start")) else (port.gone, None)
        what = LIMIT_WHAT.get(limit, what)
        return {"status": "crashed", "reason": f"{what} (at {t:.2f} s)", "limit": limit, "early": True}
    if error is not None:
        where = f"{error['file']}, line {error['line']}, " if error["line"] else ""
        reason = f"{error['type']}: {error['message']} ({where}at {t:.2f} s)"
        limit = "memory" if error["type"] == "MemoryError" else None
        return {"status": "error", "reason": reason, "limit": limit, "early": False}
    if end.get("status") == "deadlock":
        reason = (
            f"stopped: every thread of the program is waiting for another (a deadlock) at {t:.2f} s{where}"
        )
        return {"status": "hung", "reason": reason, "limit": None, "early": False}
    if end.get("status") == "time_limit":
        return {
            "status": "time_limit",
            "reason": f"ran until the time limit of {t:.2f} s{where}",
            "limit": None,
            "early": False,
        }
    return {"status": "finished", "reason": f"finished at {t:.2f} s", "limit": None, "early": False}


def run_result(
    sim: Simulation,
    shown: list[tuple[str, str]],
    ports: list[BrickPort],
    bricks: Sequence[BrickProcess | None],
    wall: float,
    session: Session | None,
) -> RunResult:
    """The run's result from its ports: shown holds each program's name as the user gave it and its
    path as its brick knew it; bricks the processes (None: a brick on another computer)."""
    t = session.world_us / 1e6 if session is not None else 0.0
    ends = []
    error = None
    for port, (name, real), brick in zip(ports, shown, bricks, strict=False):
        found = program_error(port, name, real)
        if found is not None and error is None:
            error = found
            if len(shown) > 1:
                error["robot"] = port.robot.name
        robot_t = t if port.gone or port.end is None else min(t, port.time_us / 1e6)
        threads = session.where.get(port.index) if session is not None else None
        places = shown_places(threads or (port.end or {}).get("threads"), name, real)
        where = where_text(places)
        ends.append(
            (_robot_end(port, found, brick, robot_t, where), _robot_end(port, found, brick, t, where))
        )
        ends[-1][0]["places"] = places
    # the run: the first hang, interruption or crash; else the first error; a deadlock; the time limit
    order = [e for _, e in ends if e["early"]] or [e for _, e in ends if e["status"] == "error"]
    order = order or [e for _, e in ends if e["status"] == "hung"]
    order = order or [e for _, e in ends if e["status"] == "time_limit"]
    first = order[0] if order else {"status": "finished", "reason": f"finished at {t:.2f} s", "limit": None}
    status, reason, limit = first["status"], first["reason"], first["limit"]
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
    sandbox = [
        {**((port.hello or {}).get("sandbox") or {}), **(brick.outside if brick is not None else {})}
        for port, brick in zip(ports, bricks, strict=False)
    ]
    robots = [
        {
            "robot": port.robot.name,
            "status": own["status"],
            "reason": own["reason"],
            "stopped_at": own["places"],
        }
        for port, (own, _) in zip(ports, ends, strict=False)
    ]
    notes = [
        note
        for port, (own, _) in zip(ports, ends, strict=False)
        if own["status"] in ("finished", "error") and (note := left_running(port, len(ports)))
    ]
    return RunResult(status, reason, t, wall, trace, error, limit, sandbox, robots, notes)


def left_running(port: BrickPort, robots: int = 1) -> str | None:
    """What a brick would do with the motors a program left running when it ended (brickrun, which Brickman
    starts a program with, resets every tacho motor as the program ends; a program started over SSH leaves
    them running), or None when none was."""
    running = [name for name, motor in port.robot.motors.items() if motor.state_bits & RUNNING]
    if not running:
        return None
    who = f"{port.robot.name}: " if robots > 1 else ""
    motors = f"motor {running[0]} was" if len(running) == 1 else f"motors {', '.join(running)} were"
    return (
        f"{who}the program ended while {motors} still running. On an EV3, a program started from Brickman "
        "ends with its motors reset (brickrun stops them), as this run ends; one started over SSH "
        "(`python3 prog.py`) leaves them running until something stops them. To stop the robot either "
        "way, stop them before the program ends (e.g. `tank.off()`)."
    )


def echo_line(stream, robots: int = 1, *, show: Callable[[str], str]) -> Callable[[OutputLine], None]:
    """An echo for run_programs that prints each line with its virtual time (and robot, if several).

    show(text) is the line as the stream may take it: for a terminal, with the control characters a
    program could print (escape sequences, a lone carriage return) made visible (grading/safe_text.py's
    one_line, which a front door passes: this layer cannot import it)."""

    def echo(line: OutputLine) -> None:
        who = f" robot{line.robot + 1}" if robots > 1 else ""
        stream.write(f"[{line.t_s:8.3f} s{who}] {show(line.text)}\n")

    return echo


__all__ = [
    "run_programs",
    "robot_specs",
    "RunResult",
    "ProgramError",
    "StartBlocked",
    "echo_line",
    "start_failure",
]
