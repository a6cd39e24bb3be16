"""What a program finds changed in its brick process, so that a run is the same on every machine.

Installed once, before the program is loaded (the brick process ends with the run):
- every clock and CPU-time reading, every timeout and timer follows the brick's virtual clock
  (clocks.py: `time`, `datetime`, `os.times`, `resource.getrusage`, file times, `select`,
  `signal.setitimer` ...); the time zone is UTC on every machine;
- `random` is seeded with the run's seed, and `random.seed()` with no argument,
  a new `random.Random()`, `os.urandom` and `os.getrandom` (so `secrets`, `uuid.uuid4`
  and `random.SystemRandom`) and numpy's random generators (the legacy global one,
  and `default_rng()` without a seed) draw from the run's seed too;
- `print` and writes to stderr are sent to the simulator with their virtual
  time (a printed line costs 1 ms, as on the brick's console); `input()` reads
  end-of-file; `os._exit` ends only the program, as `sys.exit` does;
- the names `site` adds to the builtins are there (`exit`, `quit`, `help`, `copyright`, `credits`,
  `license`): the brick starts Python with -S, while on an EV3 brickrun starts the program's file
  itself (its `#!/usr/bin/env python3` line), site and all.  A main thread that ends with a
  SystemExit whose code is neither None nor a number (`exit("message")`) prints it to stderr, as
  Python does as it exits (with status 1: the run ends with that error);
- `sys.argv` is the program's arguments as the simulator gives them (its welcome's "argv"), else
  `[the program's path]`;
- the machine is an EV3 running ev3dev-stretch: its host name, `os.uname()`, `platform`'s answers and
  its one CPU (machine.py);
- threads are scheduler tasks in virtual time (threads.py).
The hash seed of str and bytes is fixed by the process's environment
(PYTHONHASHSEED=0), which the simulator sets whatever its own says.
"""

from __future__ import annotations

import _sitebuiltins
import _thread
import builtins
import importlib.util
import io
import os
import random
import sys
from collections.abc import Callable

from . import identity
from .clocks import VirtualClocks
from .machine import EV3Machine
from .scheduler import Scheduler
from .threads import VirtualThreads

PRINT_US = 1_000

_real_start_new_thread = _thread.start_new_thread


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


class _AfterImport:
    """Calls fn(module) once a module is imported (at once, if it is already): a meta path finder that
    wraps the module's loader.  (A meta path finder needs only find_spec; importlib.abc would cost every
    brick 25 ms to import.)"""

    def __init__(self) -> None:
        self.calls: dict[str, list[Callable]] = {}

    def add(self, name: str, fn: Callable) -> None:
        if sys.modules.get(name) is not None:
            fn(sys.modules[name])
        self.calls.setdefault(name, []).append(fn)
        if self not in sys.meta_path:
            sys.meta_path.insert(0, self)

    def find_spec(self, name, path=None, target=None):
        calls = self.calls.get(name)
        if not calls:
            return None
        sys.meta_path.remove(self)
        try:
            spec = importlib.util.find_spec(name)
        finally:
            sys.meta_path.insert(0, self)
        if spec is None or spec.loader is None:
            return spec
        exec_module = spec.loader.exec_module

        def exec_and_call(module):
            exec_module(module)
            for fn in calls:
                fn(module)

        spec.loader = _Loader(spec.loader, exec_and_call)
        return spec


def _seed_numpy(seed: int) -> Callable:
    def seed_legacy_generator(module) -> None:
        try:
            module.seed(seed % 2**32)
        except Exception:  # noqa: BLE001 - an odd numpy: its generator stays as it is
            pass

    return seed_legacy_generator


class _Loader:
    def __init__(self, loader, exec_module) -> None:
        self._loader = loader
        self.exec_module = exec_module

    def create_module(self, spec):
        return self._loader.create_module(spec)

    def __getattr__(self, name):
        return getattr(self._loader, name)


def _deterministic_randomness(seed: int, after_import: _AfterImport) -> None:
    """random, os.urandom, os.getrandom and numpy.random, all drawn from the run's seed."""
    source = random.Random(f"ev3sim2d-urandom-{seed}")
    os.urandom = lambda size: source.randbytes(size)
    if hasattr(os, "getrandom"):
        os.getrandom = lambda size, flags=0: source.randbytes(size)
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
    after_import.add("numpy.random", _seed_numpy(seed))


class _Quitter(_sitebuiltins.Quitter):
    """site's `exit` and `quit`, called as site's are; their frame is the brick's, so that a run's traceback
    ends at the program's line, as after `sys.exit`."""

    def __call__(self, code=None):
        try:
            sys.stdin.close()
        except Exception:  # noqa: BLE001 - as site's
            pass
        raise SystemExit(code)


_Quitter.__name__ = _Quitter.__qualname__ = "Quitter"
_Quitter.__module__ = "_sitebuiltins"


def _site_builtins() -> None:
    """What `site` adds to the builtins when Python starts without -S, as it adds them on Linux."""
    import site  # (with -S, importing it runs nothing)

    builtins.exit = _Quitter("exit", "Ctrl-D (i.e. EOF)")
    builtins.quit = _Quitter("quit", "Ctrl-D (i.e. EOF)")
    site.setcopyright()
    site.sethelper()


def _as_python_exits(run: Callable[[], None]) -> Callable[[], None]:
    """run, whose SystemExit with a code that is neither None nor an int is printed to stderr, as
    Python prints it when it ends the interpreter (`exit("message")`, `sys.exit("message")`)."""

    def main() -> None:
        try:
            run()
        except SystemExit as exc:
            if exc.code is not None and not isinstance(exc.code, int) and sys.stderr is not None:
                sys.stderr.write(f"{exc.code}\n")
            raise

    return main


class BrickEnvironment:
    """Installs everything above for one program run in this process.

    argv: the program's sys.argv, when the simulator's welcome gives one (None: [program_path])."""

    def __init__(
        self,
        scheduler: Scheduler,
        link,
        seed: int,
        program_path: str,
        program_dirs: list[str],
        argv: list[str] | None = None,
    ):
        self.scheduler = scheduler
        self.link = link
        self.seed = seed
        self.program_path = program_path
        self.program_dirs = program_dirs
        self.argv = argv

    def install(self) -> None:
        s = self.scheduler
        after_import = _AfterImport()
        self.clocks = VirtualClocks(s, self.seed, _real_start_new_thread, self.link.flush)
        self.clocks.install(after_import.add)
        EV3Machine(self.clocks.in_task, self.clocks.patch).install(after_import.add)
        _deterministic_randomness(self.seed, after_import)
        _site_builtins()
        _thread.start_new_thread = self._start_new_thread
        _thread.start_new = self._start_new_thread
        self.threads = VirtualThreads(s, _real_start_new_thread)
        self.threads.install()
        self.out = ProgramOutput("stdout", self.link, s)
        self.err = ProgramOutput("stderr", self.link, s)
        sys.stdout, sys.stderr, sys.stdin = self.out, self.err, io.StringIO("")
        sys.__stdout__, sys.__stderr__, sys.__stdin__ = sys.stdout, sys.stderr, sys.stdin
        sys.argv = [self.program_path] if self.argv is None else [str(arg) for arg in self.argv]
        sys.path[:0] = [d for d in self.program_dirs if d not in sys.path]
        identity.install(self.program_dirs)
        self._real_exit = os._exit
        os._exit = self._os_exit

    def main_body(self, run: Callable[[], None]) -> Callable[[], None]:
        return self.threads.as_main_thread(_as_python_exits(run))

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
