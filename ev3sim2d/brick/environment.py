"""What a program finds changed in its brick process, so that a run is the same on every machine.

Installed once, before the program is loaded (the brick process ends with the run):
- `time.sleep/time/monotonic/perf_counter/process_time/thread_time` (and _ns forms)
  follow the brick's virtual clock, and so do `time.localtime/gmtime/ctime/asctime/
  strftime` without a time argument, and `datetime.datetime.now()/today()` and
  `datetime.date.today()`; the time zone is UTC on every machine;
- `random` is seeded with the run's seed, and `random.seed()` with no argument,
  a new `random.Random()`, `os.urandom` (so `secrets`, `uuid.uuid4` and
  `random.SystemRandom`) and numpy's random generators (the legacy global one,
  and `default_rng()` without a seed) draw from the run's seed too;
- `print` and writes to stderr are sent to the simulator with their virtual
  time (a printed line costs 1 ms, as on the brick's console); `input()` reads
  end-of-file; `os._exit` ends only the program, as `sys.exit` does;
- threads are scheduler tasks in virtual time (threads.py).
The hash seed of str and bytes is fixed by the process's environment
(PYTHONHASHSEED=0), which the simulator sets whatever its own says.
"""

from __future__ import annotations

import _thread
import datetime
import importlib.util
import io
import os
import random
import sys
import time
from collections.abc import Callable

from . import identity
from .scheduler import Scheduler
from .threads import VirtualThreads

VIRTUAL_EPOCH_S = 1_735_689_600.0  # time.time() at the start of every run: 2025-01-01 00:00 UTC
MONOTONIC_BASE_S = 1_000.0
PRINT_US = 1_000

_real_start_new_thread = _thread.start_new_thread
_real_datetime, _real_date = datetime.datetime, datetime.date


class _VirtualDatetime(datetime.datetime):
    """datetime.datetime whose now()/today() read the virtual clock (as UTC, the same on every machine)."""

    @classmethod
    def now(cls, tz=None):
        moment = _real_datetime.fromtimestamp(time.time(), datetime.timezone.utc)
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


class ProgramOutput(io.TextIOBase):
    """sys.stdout / sys.stderr of the program: each line goes to the simulator with its virtual time."""

    def __init__(self, stream_name: str, link, scheduler: Scheduler) -> None:
        self.stream_name = stream_name
        self.link = link
        self.scheduler = scheduler
        self.partial: dict[int, str] = {}

    def writable(self) -> bool:
        return True

    @property
    def encoding(self):
        return "utf-8"

    def isatty(self) -> bool:
        return False

    def write(self, text: str) -> int:
        if not isinstance(text, str):
            raise TypeError(f"write() argument must be str, not {type(text).__name__}")
        scheduler = self.scheduler
        task = scheduler.task_for_thread()
        key = id(task)
        buffered = self.partial.get(key, "") + text
        *lines, rest = buffered.split("\n")
        self.partial[key] = rest
        for line in lines:
            self.link.output(scheduler.now_us, self.stream_name, line)
            if task is not None:
                scheduler.spend(PRINT_US)
        return len(text)

    def flush(self) -> None:
        pass

    def finish(self) -> None:
        """Send what was printed without a final newline."""
        for rest in self.partial.values():
            if rest:
                self.link.output(self.scheduler.now_us, self.stream_name, rest)
        self.partial.clear()


class _SeedNumpy:
    """Seeds numpy's legacy global generator with the run's seed as soon as numpy.random is imported.
    (A meta path finder needs only find_spec; importlib.abc would cost every brick 25 ms to import.)"""

    def __init__(self, seed: int) -> None:
        self.seed = seed

    def find_spec(self, name, path=None, target=None):
        if name != "numpy.random":
            return None
        sys.meta_path.remove(self)
        try:
            spec = importlib.util.find_spec(name)
        finally:
            sys.meta_path.insert(0, self)
        if spec is None or spec.loader is None:
            return spec
        loader, seed = spec.loader, self.seed
        exec_module = loader.exec_module

        def exec_and_seed(module):
            exec_module(module)
            try:
                module.seed(seed % 2**32)
            except Exception:  # noqa: BLE001 - an odd numpy: its generator stays as it is
                pass

        spec.loader = _Loader(loader, exec_and_seed)
        return spec


class _Loader:
    def __init__(self, loader, exec_module) -> None:
        self._loader = loader
        self.exec_module = exec_module

    def create_module(self, spec):
        return self._loader.create_module(spec)

    def __getattr__(self, name):
        return getattr(self._loader, name)


def _deterministic_randomness(seed: int) -> None:
    """random, os.urandom and numpy.random, all drawn from the run's seed."""
    source = random.Random(f"ev3sim2d-urandom-{seed}")
    os.urandom = lambda size: source.randbytes(size)
    random._urandom = os.urandom  # what SystemRandom (so `secrets`, and numpy's fresh seeds) draws from
    seeds = random.Random(f"ev3sim2d-seeds-{seed}")
    real_seed = random.Random.seed

    def seed_method(self, a=None, version=2):
        if a is None:
            a = seeds.getrandbits(64)
        return real_seed(self, a, version)

    random.Random.seed = seed_method
    random.seed(seed)
    random.seed = random._inst.seed
    sys.meta_path.insert(0, _SeedNumpy(seed))


def _virtual_clock(scheduler: Scheduler) -> None:
    now = lambda: scheduler.now_us  # noqa: E731

    def sleep(seconds: float) -> None:
        if seconds < 0:
            raise ValueError("sleep length must be non-negative")
        scheduler.spend(int(round(seconds * 1e6)))

    def epoch_s() -> float:
        return VIRTUAL_EPOCH_S + now() / 1e6

    clocks: dict[str, Callable] = {
        "sleep": sleep,
        "time": epoch_s,
        "monotonic": lambda: MONOTONIC_BASE_S + now() / 1e6,
        "perf_counter": lambda: now() / 1e6,
        "process_time": lambda: now() / 1e6,
        "thread_time": lambda: now() / 1e6,
        "time_ns": lambda: int(VIRTUAL_EPOCH_S * 1e9) + now() * 1000,
        "monotonic_ns": lambda: int(MONOTONIC_BASE_S * 1e9) + now() * 1000,
        "perf_counter_ns": lambda: now() * 1000,
        "process_time_ns": lambda: now() * 1000,
        "thread_time_ns": lambda: now() * 1000,
    }
    for name, fn in clocks.items():
        fn.__name__ = name
        fn.__doc__ = getattr(time, name).__doc__
        setattr(time, name, fn)
    real = {name: getattr(time, name) for name in ("localtime", "gmtime", "ctime")}

    def at(name: str) -> Callable:
        def fn(secs=None):
            return real[name](epoch_s() if secs is None else secs)

        fn.__name__ = name
        return fn

    for name in real:
        setattr(time, name, at(name))
    real_strftime, real_asctime = time.strftime, time.asctime
    time.strftime = lambda format, t=None: real_strftime(format, time.localtime() if t is None else t)
    time.asctime = lambda t=None: real_asctime(time.localtime() if t is None else t)
    datetime.datetime, datetime.date = _VirtualDatetime, _VirtualDate


class BrickEnvironment:
    """Installs everything above for one program run in this process."""

    def __init__(self, scheduler: Scheduler, link, seed: int, program_path: str, program_dirs: list[str]):
        self.scheduler = scheduler
        self.link = link
        self.seed = seed
        self.program_path = program_path
        self.program_dirs = program_dirs

    def install(self) -> None:
        s = self.scheduler
        _virtual_clock(s)
        _deterministic_randomness(self.seed)
        _thread.start_new_thread = self._start_new_thread
        _thread.start_new = self._start_new_thread
        self.threads = VirtualThreads(s, _real_start_new_thread)
        self.threads.install()
        self.out = ProgramOutput("stdout", self.link, s)
        self.err = ProgramOutput("stderr", self.link, s)
        sys.stdout, sys.stderr, sys.stdin = self.out, self.err, io.StringIO("")
        sys.__stdout__, sys.__stderr__, sys.__stdin__ = sys.stdout, sys.stderr, sys.stdin
        sys.argv = [self.program_path]
        sys.path[:0] = [d for d in self.program_dirs if d not in sys.path]
        identity.install(self.program_dirs)
        self._real_exit = os._exit
        os._exit = self._os_exit

    def main_body(self, run: Callable[[], None]) -> Callable[[], None]:
        return self.threads.as_main_thread(run)

    def finish(self) -> None:
        self.out.finish()
        self.err.finish()

    def _os_exit(self, code: int = 0) -> None:
        if self.scheduler.task_for_thread() is None:
            self._real_exit(code)
        raise SystemExit(code)

    def _start_new_thread(self, function, args, kwargs=None):
        current = self.scheduler.task_for_thread()
        if current is None:
            return _real_start_new_thread(function, args, kwargs or {})
        name = f"{current.name}-thread{len(self.scheduler.tasks)}"
        task = self.scheduler.spawn(
            name, current.owner, lambda: function(*args, **(kwargs or {})), _real_start_new_thread
        )
        return id(task)
