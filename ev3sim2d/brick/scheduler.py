"""Virtual time in a brick: one clock, the world's ticks, and the turns of the program's tasks.

Time is counted in whole microseconds, so every run adds up the same way on
every machine.  The world advances in fixed ticks (`tick_us`).  Program tasks
(a robot's main program, and threads it starts) are real OS threads, but only
the task holding the turn runs; the others wait on their own lock.  A task
gives up the turn only when it spends virtual time (a device access, a sleep):
it is then queued by wake-up time, and the earliest task (ties: first queued)
runs next.  Before the clock moves past a tick, the tick runs.  So the order
of everything depends only on virtual time, never on the host.

A task may also *block* on a channel (a list of waiting tasks: a lock's, an
event's): it leaves the queue until another task wakes the channel, or until
its timeout, if it has one.  If every live task is blocked with no timeout,
no one can ever wake them: the run ends as a deadlock.

With a single task nothing is queued: spending time just passes the ticks
inline, which keeps the common case fast.  In a brick process, `on_tick` only
tells the simulator that the clock passed a tick (`batch_ticks`: once for the
last of several ticks passed at once, as a long sleep does); the world steps in
the simulator process.

Computing costs time too, as on the EV3's 300 MHz ARM (cpu_time.py): each line of
the program's own code a task runs costs it LINE_US, counted in slices of
SWITCH_US, the time Python's interpreter lock lets one thread compute while
another waits for it (`charge`).  A slice moves the clock for every task (one
processor); a task due meanwhile gets the turn at its end.  So a loop that never
touches a device or the clock still moves the clock, threads that compute
share it, and a few lines between two sleeps cost nothing that shows (what is
short of a slice is carried over: the same program spends the same slices in
every run).  A run that ends other than by finishing remembers where each task
of the program was (`where`).
"""

from __future__ import annotations

import heapq
import sys
import threading
from _thread import allocate_lock
from collections.abc import Callable

# The slice in which computing is charged: CPython hands its interpreter lock to a waiting thread every
# 5 ms (sys.getswitchinterval(), 0.005 s since Python 3.2, the EV3's 3.5 too).
SWITCH_US = 5_000
_current_frames = sys._current_frames  # (taken before any program runs: a program may replace sys's)


class RunOver(BaseException):
    """Raised inside a program task once the run has ended (time limit, stop)."""


class Task:
    """A thread of a program, scheduled in virtual time."""

    __slots__ = (
        "name",
        "owner",
        "main",
        "thread_id",
        "_turn",
        "done",
        "error",
        "epoch",
        "woken",
        "joiners",
        "released",
        "cpu_us",
    )

    def __init__(self, name: str, owner: object, main: bool) -> None:
        self.name = name
        self.main = main  # the run ends when every main task has ended
        self.owner = owner  # what the task acts for (the robot), opaque here
        self.thread_id: int | None = None
        self._turn = allocate_lock()  # a real lock, whatever a run does to threading
        self._turn.acquire()
        self.done = False
        self.error: BaseException | None = None
        self.epoch = 0  # queue entries from an older epoch are stale (a timeout after a wake-up)
        self.woken = False
        self.joiners: list[Task] = []  # tasks blocked until this one ends
        self.released = False  # let go for good at the end of the run
        self.cpu_us = 0  # the time it computed that is not yet charged (less than a slice)

    @property
    def thread_name(self) -> str:
        """The thread's name as the program knows it: MainThread, Thread-1 (worker), ..."""
        return self.name.split("-", 1)[1] if "-" in self.name else "MainThread"

    def __repr__(self) -> str:
        return f"Task({self.name!r})"


class Scheduler:
    """The virtual clock: ticks the world and hands the turn between tasks."""

    def __init__(
        self,
        tick_us: int,
        on_tick: Callable[[int], None],
        limit_us: int | None = None,
        batch_ticks: bool = False,
    ) -> None:
        if tick_us <= 0:
            raise ValueError("tick_us must be positive")
        self.tick_us = tick_us
        self.batch_ticks = batch_ticks
        self.on_progress: Callable[[], None] | None = None  # time passed between ticks
        self.now_us = 0
        self.next_tick_us = tick_us
        self.limit_us = limit_us
        self._on_tick = on_tick
        self._ready: list[tuple[int, int, Task, int]] = []  # (wake time, order, task, its epoch)
        self._seq = 0
        self.current: Task | None = None
        self.by_thread: dict[int, Task] = {}  # thread ident -> the task it runs
        self.tasks: list[Task] = []
        self.over = False
        self.end_reason: str | None = None
        self.settled = threading.Event()  # set once the run is over and every main task has ended
        self.program_file: Callable[[str], bool] = lambda filename: False  # the program's own code?
        self.frozen = False  # stopped in the debugger (brick/debugger.py): no time passes, nobody waits
        self.where: list[list] | None = None  # [thread, file, line] of each task, when the run ended

    # ----------------------------------------------------------------- clock
    @property
    def now_s(self) -> float:
        return self.now_us / 1e6

    def _advance_to(self, target_us: int) -> None:
        """Move the clock to target_us, running every tick on the way."""
        limit = self.limit_us
        if limit is not None and target_us > limit:
            self._advance_to(limit)
            self.end("time_limit")
            raise RunOver()
        tick_us = self.tick_us
        on_tick = self._on_tick
        if self.batch_ticks and self.next_tick_us <= target_us:
            last = self.next_tick_us + (target_us - self.next_tick_us) // tick_us * tick_us
            self.now_us = last
            self.next_tick_us = last + tick_us
            on_tick(last)
        while self.next_tick_us <= target_us:
            self.now_us = self.next_tick_us
            on_tick(self.now_us)
            self.next_tick_us += tick_us
        self.now_us = target_us

    def jump(self, tick_us: int) -> None:
        """Move the clock to a tick the connection has already passed with the simulator (a quiet wait,
        brick/link.py): no tick runs on the way."""
        self.now_us = tick_us
        self.next_tick_us = tick_us + self.tick_us

    def end(self, reason: str) -> None:
        """End the run; tasks that run again get RunOver.  Unless it finished, say where the tasks were."""
        if not self.over:
            self.over = True
            self.end_reason = reason
            if reason != "finished":
                self.where = self.positions()

    def positions(self) -> list[list]:
        """[thread name, file, line] of each live task: the innermost frame of the program's own code in
        its thread (a task in the brick's or the shim's code is where it called them)."""
        frames = _current_frames()
        found = []
        for task in self.tasks:
            frame = None if task.done or task.thread_id is None else frames.get(task.thread_id)
            while frame is not None and not self.program_file(frame.f_code.co_filename):
                frame = frame.f_back
            if frame is not None:
                found.append([task.thread_name, frame.f_code.co_filename, frame.f_lineno])
        return found

    # ----------------------------------------------------------------- tasks
    def task_for_thread(self, thread_id: int | None = None) -> Task | None:
        return self.by_thread.get(threading.get_ident() if thread_id is None else thread_id)

    def spawn(
        self, name: str, owner: object, body: Callable[[], None], start_thread: Callable, main: bool = False
    ) -> Task:
        """Create a task running body() in a new thread; it gets its first turn at the current time.

        start_thread(fn) starts fn in a new OS thread (the real _thread.start_new_thread,
        so that programs that patch threading cannot interfere).
        """
        task = Task(name, owner, main)
        self.tasks.append(task)

        def run_task() -> None:
            task.thread_id = threading.get_ident()
            self.by_thread[task.thread_id] = task
            task._turn.acquire()  # wait for the first turn
            try:
                if self.over:
                    raise RunOver()
                body()
            except RunOver:
                pass
            except BaseException as exc:  # noqa: BLE001 - handed to whoever reads the task
                task.error = exc
            finally:
                self._finish(task)

        self._queue(task, self.now_us)
        start_thread(run_task, ())
        return task

    def _queue(self, task: Task, wake_us: int) -> None:
        heapq.heappush(self._ready, (wake_us, self._seq, task, task.epoch))
        self._seq += 1

    def start(self) -> None:
        """Give the first turn (called once, from outside the tasks)."""
        self._hand_on(None)

    def spend(self, us: int) -> None:
        """The current task spends us microseconds of virtual time (may give up the turn)."""
        if self.over:
            raise RunOver()
        if self.frozen:
            return  # (looked at in the debugger: a read costs nothing, a sleep does not pass)
        target = self.now_us + us
        ready = self._ready
        if not ready or ready[0][0] > target:
            if target < self.next_tick_us and (self.limit_us is None or target <= self.limit_us):
                self.now_us = target  # the common case: no tick, nobody else due
                if self.on_progress is not None:
                    self.on_progress()
                return
            self._advance_to(target)
            return
        me = self.current
        self._queue(me, target)
        self._hand_on(me)

    def charge(self, task: Task) -> None:
        """The current task, in its thread, has computed for SWITCH_US or more (task.cpu_us): each whole
        SWITCH_US of it moves the clock, after which a task that is due takes the turn, as one waiting for
        the interpreter's lock gets it at the end of the slice."""
        if self.over:
            raise RunOver()
        if self.frozen:
            task.cpu_us = 0
            return
        slices = task.cpu_us // SWITCH_US
        task.cpu_us -= slices * SWITCH_US
        target = self.now_us + slices * SWITCH_US
        if target < self.next_tick_us and (self.limit_us is None or target <= self.limit_us):
            self.now_us = target
        else:
            self._advance_to(target)
        if self._ready and self._ready[0][0] <= self.now_us:
            self._queue(task, self.now_us)
            self._hand_on(task)

    def wait(self, predicate: Callable[[], bool], timeout_us: int | None) -> bool:
        """Spend time tick by tick until predicate() is true or timeout_us passes."""
        self._not_frozen()
        deadline = None if timeout_us is None else self.now_us + timeout_us
        while not predicate():
            if deadline is not None and self.now_us >= deadline:
                return False
            step_to = self.next_tick_us if deadline is None else min(self.next_tick_us, deadline)
            self.spend(max(step_to - self.now_us, 0) or self.tick_us)
        return True

    def block(self, channel: list[Task], timeout_us: int | None) -> bool:
        """The current task waits on channel until wake(channel) or timeout_us; True if woken."""
        if self.over:
            raise RunOver()
        self._not_frozen()
        me = self.current
        me.woken = False
        channel.append(me)
        if timeout_us is not None:
            self._queue(me, self.now_us + max(timeout_us, 0))
        try:
            self._hand_on(me)
        finally:
            if not me.woken and me in channel:
                channel.remove(me)
        return me.woken

    def _not_frozen(self) -> None:
        if self.frozen:
            raise RuntimeError("the program is stopped in the debugger: nothing it looks at may wait")

    def wake(self, channel: list[Task], n: int | None = None) -> None:
        """Make the first n (all, if None) tasks blocked on channel ready to run now."""
        count = len(channel) if n is None else min(n, len(channel))
        for task in channel[:count]:
            task.woken = True
            task.epoch += 1  # its timeout entry, if any, is stale now
            self._queue(task, self.now_us)
        del channel[:count]

    def _hand_on(self, me: Task | None) -> None:
        """Give the turn to the earliest queued task; me (if any) waits for its next turn."""
        while True:
            if not self._ready:
                if me is not None or not self._mains_done():
                    self._deadlock(me)
                return
            wake_us, _, nxt, epoch = heapq.heappop(self._ready)
            if nxt.done or epoch != nxt.epoch:
                continue
            try:
                self._advance_to(max(wake_us, self.now_us))
            except RunOver:
                if me is not None:
                    raise
                self._release_all()
                return
            break
        self.current = nxt
        if nxt is me:
            return
        nxt._turn.release()
        if me is not None:
            me._turn.acquire()
            self.current = me
            if self.over:
                raise RunOver()

    def _deadlock(self, me: Task | None) -> None:
        """Nobody is queued: every live task waits for another. End the run."""
        self.end("deadlock")
        self._release_all()
        if me is not None:
            raise RunOver()

    def _mains_done(self) -> bool:
        return all(t.done for t in self.tasks if t.main)

    def _finish(self, task: Task) -> None:
        task.done = True
        self.by_thread.pop(task.thread_id, None)
        self.wake(task.joiners)
        if not self.over and self._mains_done():
            self.end("finished")
        if self.over:
            self._release_all()
            return
        self._hand_on(None)

    def _release_all(self) -> None:
        """After the end, let every waiting task run once so it can unwind with RunOver."""
        self._ready.clear()
        for task in self.tasks:
            if not task.done and task is not self.current and not task.released:
                task.released = True
                task._turn.release()
        if self._mains_done():
            self.settled.set()

    def stop(self, reason: str) -> None:
        """End the run from outside the tasks (watchdog, Ctrl-C) and wake the waiting ones."""
        self.end(reason)
        self._release_all()
