"""Every clock a program can read in its brick, and every wait it can time, made to follow the virtual clock.

A program that reads the machine's clock (or its CPU time) does something else in each run, so two
gradings of one file would differ.  `install` runs once, from the environment (environment.py), before
the program is loaded.  In microseconds of virtual time `now` (0 when the run starts):
- wall clocks (`time.time`, CLOCK_REALTIME and its coarse and alarm forms, `datetime.now`,
  `localtime` ...): VIRTUAL_EPOCH_S + now, 2025-01-01 00:00 UTC when every run starts; CLOCK_TAI is
  37 s ahead of it.  What formats a time (`strftime`, `ctime`, `asctime`, `logging`'s `%(asctime)s`)
  formats that one, in UTC, the brick's time zone (its environment says TZ=UTC);
- steady clocks (`monotonic`, CLOCK_MONOTONIC and its raw and coarse forms, CLOCK_BOOTTIME,
  `os.times().elapsed`): MONOTONIC_BASE_S + now; `perf_counter`: now;
- CPU time (`process_time`, `thread_time`, CLOCK_PROCESS_CPUTIME_ID, CLOCK_THREAD_CPUTIME_ID, the CPU
  clock of any thread, `os.times().user`, `resource.getrusage().ru_utime`): now, as if the program used
  the brick's CPU all the time, asleep or not; system time, children's times (also those `os.wait3` and
  `wait4` give) and getrusage's counters (memory, page faults, context switches) are 0, since each
  depends on the machine;
- resolutions (`clock_getres`, `get_clock_info`): 1 us, the virtual clock's step;
- file times (`os.stat`, `lstat`, `fstat`, the entries of `os.scandir`, so `os.path.getmtime` and
  `pathlib` too): every file's times read as the moment the run began (the kernel writes a file's real
  times, which nothing in the brick can make virtual); `os.getloadavg()`: (0.0, 0.0, 0.0);
- `uuid.uuid1()`: the virtual time and a node drawn from the run's seed, not the machine's address;
- waits with a timeout (`select.select`, `poll`, `epoll`, `kqueue`, so `selectors`, `subprocess` and
  `asyncio` too; `threading`'s are threads.py's): the timeout passes in virtual time, the program's other
  threads running meanwhile.  A wait without a timeout is real only while no other thread of the
  program could run (then only another process can end it): the virtual clock stands still meanwhile;
- interval timers (`signal.setitimer`, `getitimer`, `alarm`) count virtual time.  At the deadline the
  program's process gets the timer's signal, whose default action ends it: at the same moment in every
  run.  (A program cannot handle it: `signal.signal` works only in the interpreter's main thread, and a
  program runs in a thread of its own.)  So does `faulthandler.dump_traceback_later`;
- `cProfile` (`_lsprof.Profiler` without a timer of its own) times with the virtual clock;
A fresh copy of a patched built-in module (`importlib.util.module_from_spec`) is the patched module.  A
replacement of a built-in function acts as one (BuiltinLike: it stays unbound as a class's attribute,
as `logging.Formatter.converter` is, and prints as the built-in), `datetime.now()` is a value that prints
as `datetime.datetime(...)`, and a shim module imported before this was installed (as a zygote does)
holds the replacements too.

The brick's own machinery keeps the real clocks: its modules bound the real functions when they were
imported, `select` is given back to them whole, and every replacement here that the brick itself
calls (the sandbox asks `getrusage` and `os.stat`) acts as the real one outside the program's threads.
What stays real (native code, the interpreter's internals, other processes): docs/grading-security.md.
"""

from __future__ import annotations

import _imp
import datetime
import errno
import operator
import os
import random
import select
import signal
import sys
import threading
import time
import types
from collections.abc import Callable

from .scheduler import Scheduler

try:
    import resource
except ImportError:  # (Windows)
    resource = None

_real_exit = os._exit  # (the environment makes os._exit end only the program)

VIRTUAL_EPOCH_S = 1_735_689_600  # time.time() at the start of every run: 2025-01-01 00:00 UTC
MONOTONIC_BASE_S = 1_000  # time.monotonic() at the start of every run
TAI_AHEAD_S = 37  # CLOCK_TAI - CLOCK_REALTIME since 2017
RESOLUTION_S = 1e-6  # the virtual clock counts whole microseconds
EPOCH_US = VIRTUAL_EPOCH_S * 1_000_000
MONOTONIC_US = MONOTONIC_BASE_S * 1_000_000

# The clocks `time.clock_gettime` knows, by the names this system's `time` gives them: what each reads.
CLOCK_KINDS = {
    "CLOCK_REALTIME": "wall",
    "CLOCK_TAI": "tai",
    "CLOCK_MONOTONIC": "steady",
    "CLOCK_MONOTONIC_RAW": "steady",
    "CLOCK_BOOTTIME": "steady",
    "CLOCK_UPTIME": "steady",
    "CLOCK_UPTIME_RAW": "steady",
    "CLOCK_HIGHRES": "steady",
    "CLOCK_PROCESS_CPUTIME_ID": "cpu",
    "CLOCK_THREAD_CPUTIME_ID": "cpu",
    "CLOCK_PROF": "cpu",
}
# Linux's clocks that `time` does not name: REALTIME_COARSE, MONOTONIC_COARSE, REALTIME_ALARM, BOOTTIME_ALARM
LINUX_UNNAMED_CLOCKS = {5: "wall", 6: "steady", 8: "wall", 9: "steady"}
CLOCK_INFO = {  # time.get_clock_info(name): (monotonic, adjustable)
    "time": (False, True),
    "monotonic": (True, False),
    "perf_counter": (True, False),
    "process_time": (True, False),
    "thread_time": (True, False),
}
TIMER_SIGNALS = {
    getattr(signal, which): getattr(signal, number)
    for which, number in (
        ("ITIMER_REAL", "SIGALRM"),
        ("ITIMER_VIRTUAL", "SIGVTALRM"),
        ("ITIMER_PROF", "SIGPROF"),
    )
    if hasattr(signal, which) and hasattr(signal, number)  # (a system may have one and not the other)
}
FILE_TIMES = ("st_atime", "st_mtime", "st_ctime", "st_birthtime")
SHIM_PACKAGES = (
    "ev3dev2",
    "pybricks",
)  # what a program imports of ours: it reads the clocks the program reads


class BuiltinLike:
    """A replacement of a built-in function that acts as one wherever a program could tell: a class that
    keeps it as an attribute calls it unbound, as `logging.Formatter.converter = time.localtime` needs (a
    plain function there would be a method, and every record with a time would fail), it prints as
    `<built-in function localtime>` (no address, which differs from run to run), and pickles by name."""

    def __init__(self, fn: Callable, name: str, module: str, real=None) -> None:
        self._fn = fn
        self.__name__ = self.__qualname__ = name
        self.__module__ = module
        self.__doc__ = getattr(real, "__doc__", None) or fn.__doc__
        self.__wrapped__ = fn  # (inspect.signature)

    def __call__(self, *args, **kwargs):
        return self._fn(*args, **kwargs)

    def __repr__(self) -> str:
        return f"<built-in function {self.__name__}>"

    def __reduce__(self) -> str:
        return self.__qualname__


class VirtualClocks:
    """The replacements, bound to one run's scheduler."""

    def __init__(
        self, scheduler: Scheduler, seed: int, start_thread: Callable, before_signal: Callable
    ) -> None:
        self.scheduler = scheduler
        self.seed = seed
        self.start_thread = start_thread  # the real _thread.start_new_thread
        self.before_signal = before_signal  # sends what the brick queued, before a timer's signal ends it
        self.clock_kinds = {
            getattr(time, name): kind for name, kind in CLOCK_KINDS.items() if hasattr(time, name)
        }
        if sys.platform.startswith("linux"):
            for number, kind in LINUX_UNNAMED_CLOCKS.items():
                self.clock_kinds.setdefault(number, kind)
        self.timers: dict = {}  # timer (ITIMER_*, "faulthandler") -> (deadline, interval), in virtual us
        self.timer_waits: dict = {}  # timer -> the channel its task waits on
        self.timer_fire: dict = {}  # timer -> what it does at its deadline
        self.patched: dict[str, dict[str, object]] = {}  # module name -> its replaced attributes
        self.replacing: dict[int, tuple[object, object]] = {}  # id(real) -> (real, its replacement)

    # ------------------------------------------------------------- helpers
    def in_task(self) -> bool:
        return self.scheduler.task_for_thread() is not None

    def clock_us(self, clock_id) -> int:
        """What clock `clock_id` reads now, in microseconds (OSError EINVAL for a clock there is not)."""
        clock_id = operator.index(clock_id)
        kind = self.clock_kinds.get(clock_id)
        if kind is None and clock_id < 0 and sys.platform.startswith("linux"):
            kind = "cpu"  # a thread's or a process's CPU clock (pthread_getcpuclockid, clock_getcpuclockid)
        now = self.scheduler.now_us
        if kind == "wall":
            return EPOCH_US + now
        if kind == "tai":
            return EPOCH_US + TAI_AHEAD_S * 1_000_000 + now
        if kind == "steady":
            return MONOTONIC_US + now
        if kind == "cpu":
            return now
        raise OSError(errno.EINVAL, os.strerror(errno.EINVAL))

    def wait(self, poll: Callable[[float | None], object], timeout_us: int | None):
        """poll(0) at once; then, while it finds nothing ready, again after each tick until timeout_us of
        virtual time has passed, while the program's other threads run; what it found last.  With no
        timeout (None) and no other thread of the program that could run, poll(None): only another
        process can make anything ready then, and the wait is real, the virtual clock standing still."""
        scheduler = self.scheduler
        found = poll(0)
        while not _any_ready(found) and timeout_us != 0:
            if timeout_us is None and not scheduler._ready:  # (no task queued, nor any timeout due)
                return poll(None)
            deadline = None if timeout_us is None else scheduler.now_us + timeout_us
            step_to = scheduler.next_tick_us if deadline is None else min(scheduler.next_tick_us, deadline)
            scheduler.spend(max(step_to - scheduler.now_us, 0) or scheduler.tick_us)
            found = poll(0)
            if deadline is not None:
                timeout_us = max(deadline - scheduler.now_us, 0)
        return found

    def patch(self, module: types.ModuleType, **replacements) -> None:
        """Set the module's attributes (and remember them, for a fresh copy of the module); a function that
        replaces a built-in one (or stands for one this system lacks) behaves as a built-in (BuiltinLike)."""
        for name, value in replacements.items():
            real = getattr(module, name, None)
            if isinstance(value, types.FunctionType) and (
                real is None or isinstance(real, (types.BuiltinFunctionType, BuiltinLike))
            ):
                replacements[name] = BuiltinLike(value, name, module.__name__, real)
        self.patched.setdefault(module.__name__, {}).update(replacements)
        for name, value in replacements.items():
            real = getattr(module, name, None)
            if real is not None:
                self.replacing[id(real)] = (real, value)
            setattr(module, name, value)

    # ------------------------------------------------------------- install
    def install(self, after_import: Callable[[str, Callable], None]) -> None:
        """Every replacement the module docstring lists; after_import(name, fn): fn(module) once it is imported."""
        self._keep_real_for_the_brick()
        self._time()
        self._process_times()
        self._files()
        self._waits(after_import)
        self._timers()
        self._datetime()
        after_import("_uuid", self._uuid_module)
        after_import("uuid", self._uuid)
        after_import("logging", self._logging)
        after_import("faulthandler", self._faulthandler)
        after_import("_lsprof", self._profiler)
        self._guard_fresh_copies()
        self._rebind_in_shims()

    def _rebind_in_shims(self) -> None:
        """A shim module imported before this (a zygote imports the shim once, then forks its bricks) that
        bound a clock by name, as python-ev3dev2's `from time import sleep` does, which a program's
        `from ev3dev2.sound import *` passes on, gets the virtual one, as one imported after does."""
        for name, module in list(sys.modules.items()):
            if module is None or name.split(".")[0] not in SHIM_PACKAGES:
                continue
            for key, value in list(vars(module).items()):
                found = self.replacing.get(id(value))
                if found is not None and found[0] is value:
                    setattr(module, key, found[1])

    def _keep_real_for_the_brick(self) -> None:
        """The brick's own modules (the connection's waits) keep the real `select`, whatever is patched below."""
        real = types.ModuleType("select", select.__doc__)
        real.__dict__.update({k: v for k, v in vars(select).items() if not k.startswith("__")})
        for name, module in list(sys.modules.items()):
            if name.startswith("ev3sim2d.") and module is not None and name != __name__:
                for key, value in list(vars(module).items()):
                    if value is select:
                        setattr(module, key, real)

    def _time(self) -> None:
        now = lambda: self.scheduler.now_us  # noqa: E731

        def sleep(seconds: float) -> None:
            if seconds < 0:
                raise ValueError("sleep length must be non-negative")
            self.scheduler.spend(int(round(seconds * 1e6)))

        def epoch_s() -> float:
            return VIRTUAL_EPOCH_S + now() / 1e6

        def clock_gettime(clock_id) -> float:
            return self.clock_us(clock_id) / 1e6

        def clock_gettime_ns(clock_id) -> int:
            return self.clock_us(clock_id) * 1000

        def clock_getres(clock_id) -> float:
            self.clock_us(clock_id)  # (OSError for a clock there is not)
            return RESOLUTION_S

        def get_clock_info(name: str) -> types.SimpleNamespace:
            if name not in CLOCK_INFO:
                raise ValueError("unknown clock")
            monotonic, adjustable = CLOCK_INFO[name]
            return types.SimpleNamespace(
                implementation=f"ev3sim2d virtual clock ({name})",
                monotonic=monotonic,
                adjustable=adjustable,
                resolution=RESOLUTION_S,
            )

        def pthread_getcpuclockid(thread_id: int) -> int:
            operator.index(thread_id)
            return time.CLOCK_THREAD_CPUTIME_ID  # the same number for every thread, in every run

        clocks: dict[str, Callable] = {
            "sleep": sleep,
            "time": epoch_s,
            "monotonic": lambda: MONOTONIC_BASE_S + now() / 1e6,
            "perf_counter": lambda: now() / 1e6,
            "process_time": lambda: now() / 1e6,
            "thread_time": lambda: now() / 1e6,
            "time_ns": lambda: EPOCH_US * 1000 + now() * 1000,
            "monotonic_ns": lambda: MONOTONIC_US * 1000 + now() * 1000,
            "perf_counter_ns": lambda: now() * 1000,
            "process_time_ns": lambda: now() * 1000,
            "thread_time_ns": lambda: now() * 1000,
            "get_clock_info": get_clock_info,
        }
        if hasattr(time, "clock_gettime"):
            clocks.update(
                clock_gettime=clock_gettime, clock_gettime_ns=clock_gettime_ns, clock_getres=clock_getres
            )
        if hasattr(time, "pthread_getcpuclockid"):
            clocks["pthread_getcpuclockid"] = pthread_getcpuclockid
        for name, fn in clocks.items():
            fn.__name__ = name
            fn.__doc__ = getattr(time, name).__doc__
        real = {name: getattr(time, name) for name in ("localtime", "gmtime", "ctime")}

        def at(name: str) -> Callable:
            def fn(secs=None):
                return real[name](epoch_s() if secs is None else secs)

            fn.__name__ = name
            return fn

        for name in real:
            clocks[name] = at(name)
        real_strftime, real_asctime = time.strftime, time.asctime
        clocks["strftime"] = lambda format, t=None: real_strftime(
            format, time.localtime() if t is None else t
        )
        clocks["asctime"] = lambda t=None: real_asctime(time.localtime() if t is None else t)
        self.patch(time, **clocks)
        real_steady = getattr(threading, "_time", None)
        if real_steady is not None:  # threading's own timeouts (Semaphore, Barrier, Condition.wait_for)
            steady = clocks["monotonic"]
            threading._time = lambda: steady() if self.in_task() else real_steady()

    def _process_times(self) -> None:
        """os.times, resource.getrusage and the children's rusage of os.wait3/wait4, in virtual CPU time."""
        cpu_s = lambda: self.scheduler.now_us / 1e6  # noqa: E731
        real_times = os.times

        def times() -> os.times_result:
            if not self.in_task():
                return real_times()
            return os.times_result((cpu_s(), 0.0, 0.0, 0.0, MONOTONIC_BASE_S + cpu_s()))

        times.__doc__ = real_times.__doc__
        self.patch(os, times=times)
        if resource is None:
            return
        fields = resource.struct_rusage.n_sequence_fields
        idle = resource.struct_rusage((0.0, 0.0) + (0,) * (fields - 2))
        own = {
            resource.RUSAGE_SELF,
            getattr(resource, "RUSAGE_THREAD", None),
            getattr(resource, "RUSAGE_BOTH", None),
        }
        own.discard(None)
        children = resource.RUSAGE_CHILDREN
        real_getrusage = resource.getrusage

        def getrusage(who: int) -> resource.struct_rusage:
            if not self.in_task():
                return real_getrusage(who)
            if who in own:
                return resource.struct_rusage((cpu_s(), 0.0) + (0,) * (fields - 2))
            if who == children:
                return idle
            raise ValueError("invalid who parameter")

        getrusage.__doc__ = real_getrusage.__doc__
        self.patch(resource, getrusage=getrusage)
        waits = {}
        for name in ("wait3", "wait4"):
            real_wait = getattr(os, name, None)
            if real_wait is not None:
                waits[name] = self._idle_children(real_wait, idle)
        self.patch(os, **waits)

    def _idle_children(self, real_wait: Callable, idle) -> Callable:
        def wait(*args, **kwargs):
            found = real_wait(*args, **kwargs)
            return (*found[:-1], idle) if self.in_task() else found

        wait.__name__, wait.__doc__ = real_wait.__name__, real_wait.__doc__
        return wait

    def _files(self) -> None:
        """A file's times read as the start of the run; the load average as none."""
        real = {name: getattr(os, name) for name in ("stat", "lstat", "fstat", "scandir")}

        def fixed(info: os.stat_result) -> os.stat_result:
            kind, (values, extra) = info.__reduce__()
            values = list(values)
            values[7:10] = [VIRTUAL_EPOCH_S] * 3
            for name in FILE_TIMES:
                if name in extra:
                    extra[name] = float(VIRTUAL_EPOCH_S)
                if name + "_ns" in extra:
                    extra[name + "_ns"] = EPOCH_US * 1000
            return kind(values, extra)

        def stat_like(name: str) -> Callable:
            real_stat = real[name]

            def fn(*args, **kwargs):
                info = real_stat(*args, **kwargs)
                return fixed(info) if self.in_task() else info

            fn.__name__, fn.__doc__ = name, real_stat.__doc__
            return fn

        def scandir(*args, **kwargs):
            entries = real["scandir"](*args, **kwargs)
            return _Entries(entries, fixed) if self.in_task() else entries

        scandir.__doc__ = real["scandir"].__doc__
        self.patch(
            os, stat=stat_like("stat"), lstat=stat_like("lstat"), fstat=stat_like("fstat"), scandir=scandir
        )
        if hasattr(os, "getloadavg"):
            real_load = os.getloadavg
            self.patch(os, getloadavg=lambda: (0.0, 0.0, 0.0) if self.in_task() else real_load())

    def _waits(self, after_import: Callable[[str, Callable], None]) -> None:
        """select, poll, epoll and kqueue with their timeouts in virtual time; selectors use them."""
        clocks = self
        real_select = select.select

        def select_(rlist, wlist, xlist, timeout=None):
            if not clocks.in_task():
                return real_select(rlist, wlist, xlist, timeout)
            rlist, wlist, xlist = list(rlist), list(wlist), list(xlist)
            return clocks.wait(lambda t: real_select(rlist, wlist, xlist, t), _us(timeout, "select"))

        select_.__name__, select_.__doc__ = "select", real_select.__doc__
        replaced: dict[str, object] = {"select": select_}
        if hasattr(select, "poll"):
            real_poll = select.poll

            def poll() -> _Poll:
                return _Poll(real_poll(), clocks)

            poll.__doc__ = real_poll.__doc__
            replaced["poll"] = poll
        if hasattr(select, "epoll"):
            replaced["epoll"] = _epoll_class(select.epoll, clocks)
        if hasattr(select, "kqueue"):
            replaced["kqueue"] = _kqueue_class(select.kqueue, clocks)
        self.patch(select, **replaced)
        after_import("selectors", self._selectors)

    def _selectors(self, selectors: types.ModuleType) -> None:
        """selectors bound select's functions into its classes when it was imported: bind ours."""
        chosen = getattr(selectors, "SelectSelector", None)
        if chosen is not None and isinstance(chosen.__dict__.get("_select"), types.BuiltinFunctionType):
            chosen._select = staticmethod(select.select)
        for name, cls in (("PollSelector", "poll"), ("EpollSelector", "epoll")):
            selector = getattr(selectors, name, None)
            if selector is not None and hasattr(select, cls):
                made = getattr(select, cls)
                selector._selector_cls = made if isinstance(made, type) else staticmethod(made)

    def _timers(self) -> None:
        real = {name: getattr(signal, name, None) for name in ("setitimer", "getitimer", "alarm")}
        if real["setitimer"] is None:
            return

        def setitimer(which: int, seconds: float, interval: float = 0.0) -> tuple[float, float]:
            if not self.in_task():
                return real["setitimer"](which, seconds, interval)
            return self.set_timer(which, seconds, interval)

        def getitimer(which: int) -> tuple[float, float]:
            if not self.in_task():
                return real["getitimer"](which)
            self._timer_kind(which)
            return self.timer_left(which)

        def alarm(seconds: int) -> int:
            if not self.in_task():
                return real["alarm"](seconds)
            left, _ = self.set_timer(signal.ITIMER_REAL, operator.index(seconds), 0.0)
            whole = int(left)
            return whole + (1 if left - whole >= 0.5 or (whole == 0 and left > 0) else 0)

        for fn in (setitimer, getitimer, alarm):
            fn.__doc__ = real[fn.__name__].__doc__
        self.patch(signal, setitimer=setitimer, getitimer=getitimer, alarm=alarm)
        if "_signal" in sys.modules:  # (signal's functions are _signal's)
            self.patch(sys.modules["_signal"], setitimer=setitimer, getitimer=getitimer, alarm=alarm)

    def _timer_kind(self, which) -> int:
        which = operator.index(which)
        if which not in TIMER_SIGNALS:
            raise signal.ItimerError(errno.EINVAL, os.strerror(errno.EINVAL))
        return which

    def timer_left(self, key) -> tuple[float, float]:
        """(seconds to the deadline, interval) of a timer, as getitimer gives them."""
        due = self.timers.get(key)
        if due is None:
            return (0.0, 0.0)
        deadline, interval = due
        return (max(deadline - self.scheduler.now_us, 0) / 1e6, interval / 1e6)

    def set_timer(self, which, seconds: float, interval: float) -> tuple[float, float]:
        """setitimer in virtual time: at the deadline the process gets the timer's signal."""
        which = self._timer_kind(which)
        seconds, interval = float(seconds), float(interval)
        if seconds < 0 or interval < 0:
            raise signal.ItimerError(errno.EINVAL, os.strerror(errno.EINVAL))

        def deliver() -> None:
            self.before_signal()
            os.kill(os.getpid(), TIMER_SIGNALS[which])  # its default action ends the process here

        return self.arm(which, seconds, interval, deliver)

    def arm(self, key, seconds: float, interval: float, fire: Callable[[], None]) -> tuple[float, float]:
        """Call fire() when `seconds` of virtual time have passed (then every `interval`, if not 0; 0 seconds:
        disarm), from the timer's own task (one per key, made when first armed); the timer as it was."""
        old = self.timer_left(key)
        delay_us = max(int(round(seconds * 1e6)), 1) if seconds > 0 else 0
        interval_us = max(int(round(interval * 1e6)), 1) if interval > 0 else 0
        if delay_us:
            self.timers[key] = (self.scheduler.now_us + delay_us, interval_us)
            self.timer_fire[key] = fire
        else:
            self.timers.pop(key, None)
        if key in self.timer_waits:
            self.scheduler.wake(self.timer_waits[key])
        elif delay_us:
            self.timer_waits[key] = []
            current = self.scheduler.task_for_thread()
            self.scheduler.spawn(
                f"timer-{key}", current.owner, lambda: self._run_timer(key), self.start_thread
            )
        return old

    def _run_timer(self, key) -> None:
        channel = self.timer_waits[key]
        scheduler = self.scheduler
        while True:
            due = self.timers.get(key)
            if due is None:
                scheduler.block(channel, None)
                continue
            deadline, interval = due
            if deadline > scheduler.now_us:
                scheduler.block(channel, deadline - scheduler.now_us)
                continue
            if interval:
                self.timers[key] = (deadline + interval, interval)
            else:
                del self.timers[key]
            self.timer_fire[key]()

    def _faulthandler(self, module: types.ModuleType) -> None:
        """dump_traceback_later: the traceback (and the exit, if asked) after a timeout of virtual time, not
        from a watchdog thread of real time."""
        real_later, real_cancel = module.dump_traceback_later, module.cancel_dump_traceback_later
        dump = module.dump_traceback

        def dump_traceback_later(timeout, repeat=False, file=None, exit=False):
            if not self.in_task():
                return real_later(timeout, repeat, sys.stderr if file is None else file, exit)
            timeout = float(timeout)
            if timeout <= 0:
                raise ValueError("timeout must be greater than 0")
            file = sys.stderr if file is None else file
            fd = file if isinstance(file, int) else file.fileno()  # (as faulthandler's: a real file)

            def fire() -> None:
                dump(fd, all_threads=True)
                if exit:
                    self.before_signal()
                    _real_exit(1)

            self.arm("faulthandler", timeout, timeout if repeat else 0.0, fire)

        def cancel_dump_traceback_later():
            if not self.in_task():
                return real_cancel()
            self.arm("faulthandler", 0.0, 0.0, lambda: None)
            return None

        dump_traceback_later.__doc__ = real_later.__doc__
        cancel_dump_traceback_later.__doc__ = real_cancel.__doc__
        self.patch(
            module,
            dump_traceback_later=dump_traceback_later,
            cancel_dump_traceback_later=cancel_dump_traceback_later,
        )

    def _profiler(self, module: types.ModuleType) -> None:
        """_lsprof.Profiler (so cProfile's) times with the virtual clock unless given a timer, not with the
        machine's performance counter."""
        real = module.Profiler

        class Profiler(real):
            __doc__ = real.__doc__

            def __init__(self, timer=None, timeunit=0.0, subcalls=True, builtins=True):
                if timer is None:
                    timer, timeunit = time.perf_counter, 0.0
                super().__init__(timer, timeunit, subcalls, builtins)

        Profiler.__module__, Profiler.__qualname__ = real.__module__, real.__qualname__
        self.patch(module, Profiler=Profiler)

    def _datetime(self) -> None:
        """datetime.datetime.now()/today()/utcnow() and date.today() on the virtual clock, in UTC."""
        virtual = {"datetime": _VirtualDatetime, "date": _VirtualDate}
        self.patch(datetime, **virtual)
        fast = sys.modules.get("_datetime")
        if fast is not None:
            self.patch(fast, **virtual)

    def _uuid_module(self, module: types.ModuleType) -> None:
        """_uuid.generate_time_safe (the C library's uuid1: the machine's clock and address) on the virtual clock."""
        if hasattr(module, "generate_time_safe"):

            def generate_time_safe():
                import uuid

                return uuid.uuid1().bytes, 0

            self.patch(module, generate_time_safe=generate_time_safe)

    def _uuid(self, module: types.ModuleType) -> None:
        """uuid1 from the virtual clock and a node drawn from the run's seed (no machine address)."""
        node = random.Random(f"ev3sim2d-uuid-node-{self.seed}").getrandbits(48) | (1 << 40)
        self.patch(module, _generate_time_safe=None, _node=node)

    def _logging(self, module: types.ModuleType) -> None:
        """A record's relativeCreated counts from the start of the run (logging noted its start on import)."""
        started = getattr(module, "_startTime", None)
        if isinstance(started, int):
            module._startTime = time.time_ns()
        elif isinstance(started, float):
            module._startTime = time.time()

    def _guard_fresh_copies(self) -> None:
        """importlib.util.module_from_spec(find_spec('time')) makes a new module object of a built-in or
        extension module: give the patched one instead; and patch again a module executed anew."""
        real_create = {name: getattr(_imp, name) for name in ("create_builtin", "create_dynamic")}
        real_exec = {name: getattr(_imp, name) for name in ("exec_builtin", "exec_dynamic")}
        patched = self.patched

        def create(name: str) -> Callable:
            def fn(spec, *args):
                module = sys.modules.get(getattr(spec, "name", None))
                if module is not None and spec.name in patched:
                    return module
                return real_create[name](spec, *args)

            return fn

        def execute(name: str) -> Callable:
            def fn(module):
                result = real_exec[name](module)
                for key, value in patched.get(getattr(module, "__name__", None), {}).items():
                    setattr(module, key, value)
                return result

            return fn

        for name in real_create:
            setattr(_imp, name, create(name))
        for name in real_exec:
            setattr(_imp, name, execute(name))


def _any_ready(found) -> bool:
    """Whether a poll found anything: a non-empty list, or (select) a tuple of lists, one of them not empty."""
    if isinstance(found, tuple):
        return any(found)
    return bool(found)


def _us(timeout, what: str, scale: float = 1e6) -> int | None:
    """A timeout in virtual microseconds (None: wait for ever); `scale`: microseconds per unit given."""
    if timeout is None:
        return None
    value = float(timeout)
    if value < 0:
        if what == "select":
            raise ValueError("timeout must be non-negative")
        return None  # poll, epoll: a negative timeout waits for ever
    return int(round(value * scale))


class _Poll:
    """select.poll's object, its poll(timeout in ms) in virtual time."""

    def __init__(self, real, clocks: VirtualClocks) -> None:
        self._real = real
        self._clocks = clocks

    def register(self, fd, eventmask=None):
        return self._real.register(fd) if eventmask is None else self._real.register(fd, eventmask)

    def modify(self, fd, eventmask):
        return self._real.modify(fd, eventmask)

    def unregister(self, fd):
        return self._real.unregister(fd)

    def poll(self, timeout=None):
        if not self._clocks.in_task():
            return self._real.poll(timeout)
        return self._clocks.wait(self._real.poll, _us(timeout, "poll", 1e3))


def _epoll_class(real_epoll: type, clocks: VirtualClocks) -> type:
    class epoll:  # noqa: N801 - select's name
        """select.epoll, its poll(timeout) in virtual time."""

        def __init__(self, sizehint=-1, flags=0, _real=None) -> None:
            self._real = _real if _real is not None else real_epoll(sizehint, flags)

        @classmethod
        def fromfd(cls, fd):
            return cls(_real=real_epoll.fromfd(fd))

        def __getattr__(self, name):
            return getattr(self._real, name)

        def __enter__(self):
            self._real.__enter__()
            return self

        def __exit__(self, *exc):
            return self._real.__exit__(*exc)

        def poll(self, timeout=None, maxevents=-1):
            if not clocks.in_task():
                return self._real.poll(timeout, maxevents)
            return clocks.wait(lambda t: self._real.poll(t, maxevents), _us(timeout, "epoll"))

    epoll.__doc__ = real_epoll.__doc__
    return epoll


def _kqueue_class(real_kqueue: type, clocks: VirtualClocks) -> type:  # pragma: no cover - BSD and macOS
    class kqueue:  # noqa: N801 - select's name
        """select.kqueue, its control(changes, max_events, timeout) in virtual time."""

        def __init__(self, _real=None) -> None:
            self._real = _real if _real is not None else real_kqueue()

        @classmethod
        def fromfd(cls, fd):
            return cls(_real=real_kqueue.fromfd(fd))

        def __getattr__(self, name):
            return getattr(self._real, name)

        def control(self, changelist, max_events, timeout=None):
            if not clocks.in_task():
                return self._real.control(changelist, max_events, timeout)
            first = self._real.control(changelist, max_events, 0)  # the changes, once
            if first or timeout == 0:
                return first
            return clocks.wait(lambda t: self._real.control(None, max_events, t), _us(timeout, "kqueue"))

    kqueue.__doc__ = real_kqueue.__doc__
    return kqueue


class _Entries:
    """What os.scandir gives, its entries' stat() with the run's file times."""

    def __init__(self, entries, fixed: Callable) -> None:
        self._entries = entries
        self._fixed = fixed

    def __iter__(self):
        return self

    def __next__(self) -> _Entry:
        return _Entry(next(self._entries), self._fixed)

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self._entries.close()

    def close(self) -> None:
        self._entries.close()


class _Entry:
    """An os.DirEntry whose stat() gives the run's file times."""

    __slots__ = ("_entry", "_fixed")

    def __init__(self, entry, fixed: Callable) -> None:
        self._entry = entry
        self._fixed = fixed

    name = property(lambda self: self._entry.name)
    path = property(lambda self: self._entry.path)

    def __getattr__(self, name):
        return getattr(self._entry, name)

    def __fspath__(self):
        return self._entry.__fspath__()

    def __repr__(self) -> str:
        return repr(self._entry)

    def stat(self, *, follow_symlinks: bool = True):
        return self._fixed(self._entry.stat(follow_symlinks=follow_symlinks))


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


# Named as the classes they stand for, so that a value prints as `datetime.datetime(2025, 1, 1, 0, 0)` (the
# C code prints its type's __name__, in a repr and in an error message) and pickles as datetime's own.
for _virtual, _name in ((_VirtualDatetime, "datetime"), (_VirtualDate, "date")):
    _virtual.__name__, _virtual.__qualname__, _virtual.__module__ = f"datetime.{_name}", _name, "datetime"
