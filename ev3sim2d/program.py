"""A student's program and the simulated brick it runs on: shim imports, virtual time, captured output.

While a run is on (`SimulatedEnvironment`), and only in the threads the
scheduler runs:
- `import ev3dev2` gets our shim, wherever a real python-ev3dev2 is installed;
  modules already imported are put aside and put back afterwards, so nothing
  outside the run changes;
- `time.sleep/time/monotonic/perf_counter` (and their _ns forms) follow virtual
  time, and so do `datetime.datetime.now()` and `date.today()` in modules the
  program imports (as UTC, the same on every machine); other threads keep the
  real clock;
- `print` and writes to stderr are recorded with the virtual time (a printed
  line costs 1 ms, as on the brick's console) and echoed;
- threads (`threading`, and `_thread.start_new_thread`, which MoveDifferential's
  odometry uses) are scheduler tasks, and their locks and events wait in virtual
  time (see threads.py); `input()` reads end-of-file; `random` is seeded with the
  run's seed; `os._exit` ends only the program.
"""

from __future__ import annotations

import _thread
import builtins
import datetime
import importlib
import importlib.abc
import importlib.machinery
import io
import logging
import os
import random
import sys
import time
from collections.abc import Callable
from pathlib import Path

from .scheduler import Scheduler
from .threads import VirtualThreads
from .trace import OutputLine, Trace

VIRTUAL_EPOCH_S = 1_735_689_600.0  # time.time() at the start of every run: 2025-01-01 00:00 UTC
MONOTONIC_BASE_S = 1_000.0
PRINT_US = 1_000
MAX_RECORDED_LINES = 5_000
PRELOADED_SHIM_MODULES = (
    "ev3dev2.motor",
    "ev3dev2.sensor.lego",
    "ev3dev2.sound",
    "ev3dev2.led",
    "ev3dev2.button",
)

_real_start_new_thread = _thread.start_new_thread
_real = {
    name: getattr(time, name)
    for name in ("sleep", "time", "monotonic", "perf_counter", "time_ns", "monotonic_ns", "perf_counter_ns")
}


class _VirtualDatetime(datetime.datetime):
    """datetime.datetime whose now()/today() read the virtual clock (as UTC, the same on every machine)."""

    @classmethod
    def now(cls, tz=None):
        moment = _real_datetime.fromtimestamp(time.time(), datetime.UTC)
        moment = moment.replace(tzinfo=None) if tz is None else moment.astimezone(tz)
        return cls.combine(moment.date(), moment.timetz())

    @classmethod
    def today(cls):
        return cls.now()

    @classmethod
    def utcnow(cls):
        return cls.now()


class _VirtualDate(datetime.date):
    """datetime.date whose today() reads the virtual clock."""

    @classmethod
    def today(cls):
        moment = _VirtualDatetime.now()
        return cls(moment.year, moment.month, moment.day)


_real_datetime, _real_date = datetime.datetime, datetime.date


class ProgramError(Exception):
    """A program that cannot be started (missing file, syntax error)."""


def shim_root() -> Path:
    """The folder that holds our `ev3dev2` package (installed copy first, then the source tree)."""
    package = Path(__file__).resolve().parent
    for root in (package / "_shim", package.parent):
        if (root / "ev3dev2" / "__init__.py").exists():
            return root
    raise RuntimeError(f"ev3sim2d is incomplete: no ev3dev2 shim next to {package}")


class Program:
    """A program file compiled as `__main__`, its folder importable."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        try:
            self.source = self.path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise ProgramError(f"{path}: no such program file") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise ProgramError(f"{path}: cannot read the program ({exc})") from None
        try:
            self.code = compile(self.source, str(self.path), "exec", dont_inherit=True)
        except SyntaxError as exc:
            where = f"{exc.filename}, line {exc.lineno}" if exc.lineno else str(self.path)
            raise ProgramError(f"{where}: {exc.msg}\n    {(exc.text or '').rstrip()}") from None

    def run(self) -> None:
        module = {"__name__": "__main__", "__file__": str(self.path), "__builtins__": builtins}
        exec(self.code, module)


class ShimFinder(importlib.abc.MetaPathFinder):
    """Finds `ev3dev2` in our shim folder before anything on sys.path."""

    def __init__(self, root: Path) -> None:
        self.root = str(root)

    def find_spec(self, name, path=None, target=None):
        if name == "ev3dev2":
            return importlib.machinery.PathFinder.find_spec(name, [self.root])
        return None


class ProgramOutput(io.TextIOBase):
    """sys.stdout / sys.stderr during a run: lines from program tasks go to the trace, with their time."""

    def __init__(self, stream_name: str, real, env: SimulatedEnvironment) -> None:
        self.stream_name = stream_name
        self.real = real
        self.env = env
        self.partial: dict[int, str] = {}

    def writable(self) -> bool:
        return True

    @property
    def encoding(self):
        return "utf-8"

    def write(self, text: str) -> int:
        scheduler = self.env.scheduler
        task = scheduler.task_for_thread()
        if task is None or self.env.echoing:
            return self.real.write(text)
        key = id(task)
        buffered = self.partial.get(key, "") + text
        *lines, rest = buffered.split("\n")
        self.partial[key] = rest
        for line in lines:
            self.env.emit(OutputLine(scheduler.now_s, self.env.robot_index(task), self.stream_name, line))
            scheduler.spend(PRINT_US)
        return len(text)

    def flush(self) -> None:
        task = self.env.scheduler.task_for_thread()
        if task is None:
            self.real.flush()

    def finish(self) -> None:
        """Record what was printed without a final newline."""
        for key, rest in list(self.partial.items()):
            if rest:
                task = next((t for t in self.env.scheduler.tasks if id(t) == key), None)
                index = self.env.robot_index(task) if task else 0
                self.env.emit(OutputLine(self.env.scheduler.now_s, index, self.stream_name, rest))
        self.partial.clear()


class SimulatedEnvironment:
    """Everything a program sees changed while it runs in the simulator; undone on exit."""

    def __init__(
        self,
        scheduler: Scheduler,
        link,
        trace: Trace,
        robots: list,
        seed: int,
        program_dirs: list[Path],
        echo: Callable[[OutputLine], None] | None = None,
    ) -> None:
        self.scheduler = scheduler
        self.link = link
        self.trace = trace
        self.robots = robots
        self.seed = seed
        self.program_dirs = [str(d) for d in program_dirs]
        self.echo = echo
        self.echoing = False  # while the echo runs, its own prints go to the real streams
        self.dropped_lines = 0

    # ------------------------------------------------------------- output
    def robot_index(self, task) -> int:
        try:
            return self.robots.index(task.owner)
        except ValueError:
            return 0

    def emit(self, line: OutputLine) -> None:
        if len(self.trace.output) < MAX_RECORDED_LINES:
            self.trace.add_output(line)
        else:
            self.dropped_lines += 1
        if self.echo is not None:
            self.echoing = True
            try:
                self.echo(line)
            finally:
                self.echoing = False

    # ------------------------------------------------------- virtual time
    def _clock(self, real: Callable, virtual: Callable) -> Callable:
        by_thread = self.scheduler.task_for_thread

        def clock(*args):
            if by_thread() is None:
                return real(*args)
            return virtual(*args)

        clock.__name__ = real.__name__
        clock.__doc__ = real.__doc__
        return clock

    def _sleep(self, seconds: float) -> None:
        if seconds < 0:
            raise ValueError("sleep length must be non-negative")
        self.scheduler.spend(int(round(seconds * 1e6)))

    def _start_new_thread(self, function, args, kwargs=None):
        current = self.scheduler.task_for_thread()
        if current is None:
            return _real_start_new_thread(function, args, kwargs or {})
        name = f"{current.name}-thread{len(self.scheduler.tasks)}"
        task = self.scheduler.spawn(
            name, current.owner, lambda: function(*args, **(kwargs or {})), _real_start_new_thread
        )
        return id(task)

    # --------------------------------------------------------- enter/exit
    def __enter__(self) -> SimulatedEnvironment:
        s = self.scheduler
        self._saved_modules = {
            k: sys.modules.pop(k) for k in list(sys.modules) if k == "ev3dev2" or k.startswith("ev3dev2.")
        }
        self._finder = ShimFinder(shim_root())
        sys.meta_path.insert(0, self._finder)
        self._shim_link = importlib.import_module("ev3dev2._link")
        self._shim_link.connect(self.link)

        now = lambda: s.now_us  # noqa: E731
        virtual = {
            "sleep": self._sleep,
            "time": lambda: VIRTUAL_EPOCH_S + now() / 1e6,
            "monotonic": lambda: MONOTONIC_BASE_S + now() / 1e6,
            "perf_counter": lambda: now() / 1e6,
            "time_ns": lambda: int(VIRTUAL_EPOCH_S * 1e9) + now() * 1000,
            "monotonic_ns": lambda: int(MONOTONIC_BASE_S * 1e9) + now() * 1000,
            "perf_counter_ns": lambda: now() * 1000,
        }
        for name, fn in virtual.items():
            setattr(time, name, self._clock(_real[name], fn))
        _thread.start_new_thread = self._start_new_thread
        _thread.start_new = self._start_new_thread
        self._threads = VirtualThreads(s, _real_start_new_thread)
        self._threads.install()
        # loading is start-up, not the program's time; after the patches, so that the
        # shim's own `from time import sleep` gets the virtual one
        for module in PRELOADED_SHIM_MODULES:
            importlib.import_module(module)

        self._saved_streams = (sys.stdout, sys.stderr, sys.stdin)
        self._out = ProgramOutput("stdout", sys.stdout, self)
        self._err = ProgramOutput("stderr", sys.stderr, self)
        sys.stdout, sys.stderr, sys.stdin = self._out, self._err, io.StringIO("")
        datetime.datetime, datetime.date = _VirtualDatetime, _VirtualDate
        self._saved_exit = os._exit
        os._exit = self._os_exit
        self._saved_random = random.getstate()
        random.seed(self.seed)
        self._saved_path = list(sys.path)
        sys.path[:0] = [d for d in self.program_dirs if d not in sys.path]
        self._saved_logging = _logging_state()
        return self

    def main_body(self, program: Program) -> Callable[[], None]:
        """What a program's main task runs: the program, as its main thread."""
        return self._threads.as_main_thread(program.run)

    def _os_exit(self, code: int = 0) -> None:
        if self.scheduler.task_for_thread() is None:
            self._saved_exit(code)
        raise SystemExit(code)

    def __exit__(self, *exc) -> None:
        _restore_logging(self._saved_logging)
        self._out.finish()
        self._err.finish()
        sys.stdout, sys.stderr, sys.stdin = self._saved_streams
        for name, fn in _real.items():
            setattr(time, name, fn)
        _thread.start_new_thread = _real_start_new_thread
        _thread.start_new = _real_start_new_thread
        self._threads.uninstall()
        os._exit = self._saved_exit
        datetime.datetime, datetime.date = _real_datetime, _real_date
        random.setstate(self._saved_random)
        sys.path[:] = self._saved_path
        self._shim_link.disconnect()
        if self._finder in sys.meta_path:
            sys.meta_path.remove(self._finder)
        for k in [k for k in sys.modules if k == "ev3dev2" or k.startswith("ev3dev2.")]:
            del sys.modules[k]
        sys.modules.update(self._saved_modules)


def _logging_state() -> dict:
    """Handlers and levels of every logger: a program's logging.basicConfig must not outlive its run."""
    loggers = [
        logging.root,
        *(lg for lg in logging.root.manager.loggerDict.values() if isinstance(lg, logging.Logger)),
    ]
    return {
        "disable": logging.root.manager.disable,
        "loggers": {id(lg): (lg, list(lg.handlers), lg.level, lg.propagate, lg.disabled) for lg in loggers},
    }


def _restore_logging(state: dict) -> None:
    logging.disable(state["disable"])
    known = state["loggers"]
    for lg in [logging.root, *logging.root.manager.loggerDict.values()]:
        if not isinstance(lg, logging.Logger):
            continue
        if id(lg) in known:
            _, handlers, level, propagate, disabled = known[id(lg)]
            lg.handlers[:] = handlers
            lg.setLevel(level)
            lg.propagate, lg.disabled = propagate, disabled
        else:
            lg.handlers.clear()
