"""One program's run inside its brick process: the clock, the link, the shim, the program's main task.

The brick's scheduler turns the program's threads in virtual time; each time
its clock passes a tick it tells the simulator (link.tick), which steps the
world in lockstep.  The run ends when every main task has ended, on a deadlock,
or when the simulator stops it (at its time limit, which the brick is not told:
nothing in here says which world or variant this is); the `end` message says
which, and carries the program's error if it had one.
"""

from __future__ import annotations

import gc
import importlib
import io
import os
import sys
import time

from ..protocol import ProtocolError
from .environment import BrickEnvironment, _real_start_new_thread
from .link import BrickLink
from .program import Program, ending, error_report
from .scheduler import Scheduler

_monotonic = time.monotonic  # the real clock (the program's is virtual)

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
)


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
        importlib.import_module("ev3dev2._link").connect(self.link)
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
        task = s.spawn("robot", None, self.env.main_body(program.run), _real_start_new_thread, main=True)
        s.start()
        s.settled.wait()
        self.env.finish()
        how = ending([task], self.program_path, s)
        if self.link.stopped:
            how["status"] = "stopped"
        self._end(how)

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
