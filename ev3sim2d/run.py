"""One run: programs drive their robots in a world until they end, the time limit, or a hang.

Each program is a main task of the scheduler on a robot of its own (program i
starts at the world's start pose i).  This thread only watches: it waits for
the run to settle, and stops a program that spins without touching the robot
or the clock for `hang_after_s` seconds of real time.  Whatever happens, the
result holds the trace up to that moment.
"""

from __future__ import annotations

import ctypes
import gc
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from .link import ShimLink
from .program import Program, ProgramError, SimulatedEnvironment, _real_start_new_thread
from .scheduler import RunOver, Scheduler
from .simulation import Simulation, StartBlocked
from .trace import OutputLine, Trace
from .world.robot_spec import RobotSpec
from .world.world import World

_real_monotonic = time.monotonic
_real_perf_counter = time.perf_counter
PACKAGE_DIR = str(Path(__file__).resolve().parent)


class ProgramHung(RunOver):
    """Raised in a program that spun without using the robot or the clock."""


@dataclass
class RunResult:
    """How a run ended, and what happened in it."""

    status: str  # finished, error, time_limit, hung, interrupted
    reason: str  # one line for the terminal
    sim_time_s: float
    wall_time_s: float
    trace: Trace | None
    error: dict | None = None  # type, message, file, line, t_s, traceback
    stray_threads: int = 0  # program threads that would not stop (the process must exit hard)

    @property
    def ok(self) -> bool:
        return self.status in ("finished", "time_limit")


def _describe_devices(robot) -> str:
    parts = [f"{p} {m.kind} motor" for p, m in robot.motors.items()]
    parts += [f"{p} {s.spec.kind} sensor" for p, s in robot.sensors.items()]
    return ", ".join(parts)


def _error_report(exc: BaseException, program: Program, t_s: float, robot) -> dict:
    """The program's exception, its traceback cut to the program's and the shim's frames."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if not f.filename.startswith(PACKAGE_DIR)]
    text = "Traceback (most recent call last):\n" + "".join(traceback.format_list(frames))
    text += "".join(traceback.format_exception_only(type(exc), exc))
    own = [f for f in frames if Path(f.filename) == program.path]
    where = own[-1] if own else (frames[-1] if frames else None)
    message = str(exc)
    hint = None
    if type(exc).__name__ == "DeviceNotFound":
        hint = f"this robot has: {_describe_devices(robot)}"
    return {
        "type": type(exc).__name__,
        "message": message,
        "file": str(program.path) if own else (where.filename if where else None),
        "line": where.lineno if where else None,
        "t_s": t_s,
        "traceback": text,
        "hint": hint,
    }


def run_programs(
    programs: list[str | Path],
    world: World,
    robot: RobotSpec | None = None,
    time_limit_s: float | None = 60.0,
    seed: int = 0,
    hang_after_s: float = 5.0,
    echo=None,
    presses: list | None = None,
) -> RunResult:
    """Run each program on its own robot in the world; see the module docstring.

    presses: scripted button presses (ButtonPress), added to the world file's.
    """
    loaded = [Program(p) for p in programs]  # ProgramError: the caller reports it
    if len(loaded) > len(world.starts):
        raise ProgramError(
            f"{len(loaded)} programs but the world '{world.name}' has {len(world.starts)} start pose(s); "
            f"add starts to the world file or run fewer programs"
        )
    spec = robot or world.robot
    names = ["robot"] if len(loaded) == 1 else [f"robot{i + 1}" for i in range(len(loaded))]
    sim = Simulation(world, [(names[i], spec, world.starts[i]) for i in range(len(loaded))], seed=seed)
    limit_us = None if time_limit_s is None else int(round(time_limit_s * 1e6))
    scheduler = Scheduler(sim.tick_us, sim.tick, limit_us)
    presses = sorted([*world.buttons, *(presses or ())], key=lambda p: p.at_s)
    sim.trace.world["buttons"] = [[p.button, p.at_s, p.hold_s] for p in presses]
    link = ShimLink(scheduler, sim.trace, sim.robots, presses)
    env = SimulatedEnvironment(
        scheduler, link, sim.trace, sim.robots, seed, sorted({p.path.resolve().parent for p in loaded}), echo
    )
    tasks = []
    with env:
        for program, bot in zip(loaded, sim.robots, strict=False):
            tasks.append(
                scheduler.spawn(bot.name, bot, env.main_body(program), _real_start_new_thread, main=True)
            )
        wall_start = _real_perf_counter()
        scheduler.start()
        status_override = _watch(scheduler, hang_after_s)
    wall = _real_perf_counter() - wall_start
    result = _result(scheduler, sim, loaded, tasks, wall, status_override, env.dropped_lines)
    del sim, env, link, scheduler, tasks
    gc.collect()  # free the pymunk world now: left to interpreter exit, its teardown complains
    return result


def _watch(scheduler: Scheduler, hang_after_s: float) -> str | None:
    """Wait for the run to settle; stop it if it hangs or the user interrupts it."""
    last = scheduler.now_us  # a program that uses the robot or the clock moves it
    last_change = _real_monotonic()
    try:
        while not scheduler.settled.wait(0.05):
            seen = scheduler.now_us
            now = _real_monotonic()
            if seen != last:
                last, last_change = seen, now
            elif now - last_change > hang_after_s:
                _stop_hung(scheduler)
                return "hung"
    except KeyboardInterrupt:
        scheduler.stop("interrupted")
        _interrupt(scheduler, RunOver)
        scheduler.settled.wait(1.0)
        return "interrupted"
    return None


def _interrupt(scheduler: Scheduler, exc_type: type) -> None:
    for task in scheduler.tasks:
        if not task.done and task.thread_id is not None:
            ctypes.pythonapi.PyThreadState_SetAsyncExc(
                ctypes.c_ulong(task.thread_id), ctypes.py_object(exc_type)
            )


def _stop_hung(scheduler: Scheduler) -> None:
    """Stop a spinning program: raise ProgramHung in it, a few times if it catches it."""
    scheduler.stop("hung")
    for _ in range(10):
        _interrupt(scheduler, ProgramHung)
        if scheduler.settled.wait(0.2):
            return


def _result(scheduler, sim, programs, tasks, wall, status_override, dropped_lines) -> RunResult:
    t = scheduler.now_s
    error = None
    for task, program in zip(tasks, programs, strict=False):
        exc = task.error
        if exc is None or isinstance(exc, RunOver):
            continue
        if isinstance(exc, SystemExit) and exc.code in (None, 0):
            continue
        if error is None:
            error = _error_report(exc, program, t, task.owner)
            if len(programs) > 1:
                error["robot"] = task.owner.name
    if status_override == "hung":
        status = "hung"
        reason = (
            f"stopped: the program ran for a while without using the robot or the clock "
            f"(a loop with no sensor read, motor command or sleep?) at {t:.2f} s"
        )
    elif status_override == "interrupted":
        status, reason = "interrupted", f"interrupted at {t:.2f} s"
    elif error is not None:
        status = "error"
        where = f"{error['file']}, line {error['line']}, " if error["line"] else ""
        reason = f"{error['type']}: {error['message']} ({where}at {t:.2f} s)"
    elif scheduler.end_reason == "deadlock":
        status = "hung"
        reason = f"stopped: every thread of the program is waiting for another (a deadlock) at {t:.2f} s"
    elif scheduler.end_reason == "time_limit":
        status, reason = "time_limit", f"ran until the time limit of {t:.2f} s"
    else:
        status, reason = "finished", f"finished at {t:.2f} s"
    sim.finish()
    sim.trace.result = {
        "status": status,
        "reason": reason,
        "sim_time_s": t,
        "error_type": error["type"] if error else None,
        "error": error,
        "dropped_output_lines": dropped_lines,
    }
    stray = sum(1 for task in tasks if not task.done)
    return RunResult(status, reason, t, wall, sim.trace, error, stray)


def echo_line(stream, robots: int = 1) -> Callable[[OutputLine], None]:
    """An echo for run_programs that prints each line with its virtual time (and robot, if several)."""

    def echo(line: OutputLine) -> None:
        who = f" robot{line.robot + 1}" if robots > 1 else ""
        stream.write(f"[{line.t_s:8.3f} s{who}] {line.text}\n")

    return echo


__all__ = ["run_programs", "RunResult", "ProgramError", "StartBlocked", "echo_line"]
