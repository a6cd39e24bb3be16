"""One program's run inside its brick process: the clock, the link, the shim, the program's main task.

The brick's scheduler turns the program's threads in virtual time; each time
its clock passes a tick it tells the simulator (link.tick), which steps the
world in lockstep.  The run ends when every main task has ended, on a deadlock,
or when the simulator stops it (at its time limit, which the brick is not told:
nothing in here says which world or variant this is); the `end` message says
which, and carries the program's error if it had one, or, for a run stopped,
where each of the program's threads was.  The program's own lines cost time as
they run (cpu_time.py).  While the program runs, this process's main
thread looks now and then whether its clock stands still outside the
simulation (a real lock, a pipe): if the simulator stops it then, the main
thread answers for it.
"""

from __future__ import annotations

import gc
import importlib
import io
import os
import sys
import time
from collections.abc import Callable

from ..protocol import ProtocolError
from .cpu_time import CpuTime
from .debugger import BrickDebugger
from .environment import BrickEnvironment, _real_start_new_thread
from .link import BrickLink
from .program import Program, ending, error_report
from .program_kind import ProgramKind
from .scheduler import Scheduler

_monotonic = time.monotonic  # the real clock (the program's is virtual)
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))  # ev3sim2d
SHIMS = ("ev3dev2", "pybricks")
WATCH_S = 0.25  # real seconds between two looks of the main thread at a program whose clock stands still

SHIM_MODULES = (
    "ev3dev2",
    "ev3dev2.motor",
    "ev3dev2.sensor",
    "ev3dev2.sensor.lego",
    "ev3dev2.sound",
    "ev3dev2.led",
    "ev3dev2.button",
    "ev3dev2.power",
    "ev3dev2.port",
    "ev3dev2.unit",
    "ev3dev2.wheel",
    "ev3dev2.stopwatch",
    "pybricks",
    "pybricks._link",
    "pybricks._arguments",
    "pybricks._media_files",
    "pybricks.parameters",
    "pybricks._sensor",
    "pybricks._ev3_sensors",
    "pybricks._motor",
    "pybricks.ev3devices",
    "pybricks.nxtdevices",
    "pybricks.iodevices",
    "pybricks.robotics",
    "pybricks.tools",
    "pybricks._image",  # (reads its fonts when imported: before the sandbox)
    "pybricks._speaker",
    "pybricks.hubs",
    "pybricks.media",
    "pybricks.media.ev3dev",
    "pybricks.speaker",
    "pybricks.display",
    "pybricks.messaging",
)  # (not pybricks.ev3brick: importing it makes an EV3Brick and clears the screen, as on a brick)


class BrickRun:
    """The program of one robot, run in this process against the simulator at the other end of channel."""

    def __init__(self, channel, config: dict) -> None:
        self.channel = channel
        self.config = config
        self.program_path = config["program"]

    def prepare(self) -> None:
        """Everything that needs files the sandbox will hide: clock patches first, then the shim."""
        config = self.config
        self.scheduler = Scheduler(config["tick_us"], self._tick, config.get("limit_us"), batch_ticks=True)
        self.link = BrickLink(self.channel, self.scheduler)
        self.link.quiet = config.get("quiet", True) is not False
        self.env = BrickEnvironment(
            self.scheduler,
            self.link,
            config.get("seed", 0),
            self.program_path,
            config.get("program_dirs", []),
            argv=config.get("argv"),
        )
        self.env.install()
        for name in SHIM_MODULES:
            importlib.import_module(name)
        for shim in SHIMS:
            importlib.import_module(shim + "._link").connect(self.link)
        gc.freeze()  # the runtime and the shim: the program's collections need not look at them

    def _forked(self) -> None:
        """A process the program forked is not the brick: it never writes to the connection (its use of
        a device or of the clock ends it), and what it prints goes to the console, as a brick's own
        start-up messages do."""
        self.link.detach()
        sys.stdout = io.TextIOWrapper(io.FileIO(1, "w", closefd=False), "utf-8", "backslashreplace")
        sys.stderr = io.TextIOWrapper(io.FileIO(2, "w", closefd=False), "utf-8", "backslashreplace")

    def _tick(self, tick_us: int) -> None:
        self.link.tick(tick_us)

    def run(self) -> None:
        s = self.scheduler
        if hasattr(os, "register_at_fork"):  # (after the sandbox's own forks: they run the program)
            os.register_at_fork(after_in_child=self._forked)
        try:
            program = Program.read(self.program_path)  # as Python reads a file: BOM, coding line, line ends
        except (OSError, SyntaxError, ValueError, RecursionError, MemoryError) as exc:
            # (compiling is the only place a program's source is parsed: here, under the brick's limits)
            report = {**error_report(exc, self.program_path, 0.0), "compiling": True}
            report["file"] = report["file"] or self.program_path  # (a source too deep has no line)
            self._end({"t_us": 0, "status": "error", "error": report})
            return
        if not self._one_shim(program):
            return
        self._count_lines(program)
        body = self._debugging(program.run)
        task = s.spawn("robot", None, self.env.main_body(body), _real_start_new_thread, main=True)
        s.start()
        if not self._watch():
            return
        self.env.finish()
        how = ending([task], self.program_path, s)
        if self.link.stopped:
            how["status"] = "stopped"
        self._end(how)

    def _one_shim(self, program: Program) -> bool:
        """The program's file imports one shim, not both (program_kind.py): else it ends before it starts,
        with the error at the import that disagrees.  A program that is not python-ev3dev2's finds
        MicroPython's module names (utime, urandom, uerrno...) as EV3 MicroPython has them."""
        self.kind = ProgramKind()
        mixed = self.kind.check(program.code, self.program_path)
        if mixed is not None:
            line, message = mixed
            where = f'  File "{self.program_path}", line {line}, in <module>\n'
            report = {"type": "ImportError", "message": message, "file": self.program_path, "line": line}
            report |= {
                "t_s": 0.0,
                "traceback": f"Traceback (most recent call last):\n{where}ImportError: {message}",
            }
            self._end({"t_us": 0, "status": "error", "error": report})
            return False
        if self.kind.shim != "ev3dev2":
            shim_root = self.config.get("shim_root") or os.path.dirname(PACKAGE_DIR)
            sys.path.append(os.path.join(shim_root, "pybricks", "_micropython"))
        return True

    def _count_lines(self, program: Program) -> None:
        """From now on the program's lines cost time: its file compiled again to count them, and its modules
        imported so.  (A source that compiles but is too deep to count runs uncounted.)"""
        cpu = self._cpu_time()
        cpu.install()
        try:
            with open(self.program_path, "rb") as f:
                program.code = cpu.compile(f.read(), self.program_path)
        except (OSError, SyntaxError, ValueError, RecursionError, MemoryError):
            pass

    def _debugging(self, run: Callable[[], None]) -> Callable[[], None]:
        """breakpoint() as the welcome says (`debug`): a stop in the brick's debugger (brick/debugger.py),
        or nothing, as PYTHONBREAKPOINT=0 makes it (grading, serving); with "start", the program stops
        at its first line."""
        mode = self.config.get("debug")
        if mode not in ("breakpoints", "start"):
            sys.breakpointhook = _no_breakpoint
            return run
        debugger = BrickDebugger(self.link, self.scheduler, os.path.dirname(self.program_path))
        sys.breakpointhook = debugger.breakpoint
        if mode == "breakpoints":
            return run

        def started() -> None:
            debugger.start()
            run()

        return started

    def _cpu_time(self) -> CpuTime:
        """The program's own code: its files, not the brick's, the shims', Python's nor third parties' (even
        in the program's folder)."""
        shim_root = self.config.get("shim_root") or os.path.dirname(PACKAGE_DIR)
        outside = [
            PACKAGE_DIR,
            os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
            *(os.path.join(shim_root, name) for name in SHIMS),
            os.path.dirname(os.__file__),  # the standard library
            *self.config.get("site_packages", ()),
        ]
        return CpuTime(self.scheduler, self.config.get("program_dirs", []), outside, self.kind)

    def _watch(self) -> bool:
        """Wait for the end of the run; True once it has ended.  False if this thread answered the simulator's
        stop for the program, saying where its threads were: when the program is stuck outside the
        simulation (its clock still, reading nothing from the simulator), or has not ended within WATCH_S
        of the stop (it catches the exception that ends it, or is stuck in a long call)."""
        s, link = self.scheduler, self.link
        clock, looks_since_stop = s.now_us, 0
        while not s.settled.wait(WATCH_S):
            if link.stopped is not None:
                looks_since_stop += 1
                if looks_since_stop < 2:
                    continue
            elif s.now_us != clock:
                clock = s.now_us
                continue
            else:
                why = link.stop_waiting()
                if why is None:
                    continue
                link.stopped = why
                s.stop("stopped")
            self.env.finish()
            self._end({**ending(s.tasks[:1], self.program_path, s), "status": "stopped"})
            return False
        return True

    def _end(self, how: dict) -> None:
        try:
            self.link.flush()
            self.channel.send(["end", how])
        except ProtocolError:
            pass
        # wait until the simulator has read everything (it says stop or closes), but not for ever
        end = _monotonic() + 5.0
        try:
            while True:
                message = self.channel.receive(timeout_s=max(0.0, end - _monotonic()))
                if message is None or message[0] == "stop":
                    return
        except ProtocolError:
            pass


def _no_breakpoint(*args, **kwargs) -> None:
    """breakpoint() where nobody debugs: nothing, as with PYTHONBREAKPOINT=0."""
