"""A program's threads in virtual time: `threading`'s primitives rebuilt on the scheduler.

While a run is on, a thread a program starts is a scheduler task, and the
program's locks, events, conditions and semaphores wait in virtual time:
a task that waits gives the turn to the others and is woken, at the virtual
time it is released, by the task that releases it.  So a program with
threads runs as on the brick, but in the same order every time.

Only objects made inside a program task are virtual; the simulator's own
threads keep using the real primitives.  `Thread.start/join/is_alive` are
patched on the class for the duration of the run, so subclasses of
`threading.Thread` defined by the program work too.  A non-daemon thread
keeps the program alive after its main code ends, as in Python; daemon
threads (and `_thread.start_new_thread`) end with it.
"""

from __future__ import annotations

import queue
import threading
import time as _time_module
from collections.abc import Callable

from .scheduler import RunOver, Scheduler


class VirtualThreads:
    """Installs the virtual primitives into `threading` (and `queue`) and takes them out again."""

    def __init__(self, scheduler: Scheduler, start_thread: Callable) -> None:
        self.scheduler = scheduler
        self.start_thread = start_thread  # the real _thread.start_new_thread
        self.tasks: dict[threading.Thread, object] = {}

    def in_task(self) -> bool:
        return self.scheduler.task_for_thread() is not None

    def _us(self, timeout: float | None) -> int | None:
        if timeout is None or timeout < 0:
            return None
        return int(round(timeout * 1e6))

    # ------------------------------------------------------- install/remove
    def install(self) -> None:
        vt = self
        real = {
            name: getattr(threading, name)
            for name in ("Lock", "RLock", "Condition", "Event", "Semaphore", "BoundedSemaphore")
        }
        self._saved = real
        self._saved_methods = (threading.Thread.start, threading.Thread.join, threading.Thread.is_alive)
        self._saved_queue_time = getattr(queue, "time", None)
        self._saved_simple_queue = queue.SimpleQueue

        def factory(name: str, virtual: type) -> Callable:
            original = real[name]

            def make(*args, **kwargs):
                return virtual(vt, *args, **kwargs) if vt.in_task() else original(*args, **kwargs)

            make.__name__ = name
            return make

        threading.Lock = factory("Lock", VLock)
        threading.RLock = factory("RLock", VRLock)
        threading.Condition = factory("Condition", VCondition)
        threading.Event = factory("Event", VEvent)
        threading.Semaphore = factory("Semaphore", VSemaphore)
        threading.BoundedSemaphore = factory("BoundedSemaphore", VBoundedSemaphore)
        start, join, is_alive = self._saved_methods

        def patched_start(thread):
            return vt.start(thread) if vt.in_task() else start(thread)

        def patched_join(thread, timeout=None):
            return vt.join(thread, timeout) if thread in vt.tasks else join(thread, timeout)

        def patched_is_alive(thread):
            task = vt.tasks.get(thread)
            return is_alive(thread) if task is None else thread._started.is_set() and not task.done

        threading.Thread.start, threading.Thread.join, threading.Thread.is_alive = (
            patched_start,
            patched_join,
            patched_is_alive,
        )
        if self._saved_queue_time is not None:
            queue.time = _time_module.monotonic  # the virtual clock, patched already by the environment
        # queue.SimpleQueue is C's, waiting on a real lock (concurrent.futures' and multiprocessing.pool's
        # ThreadPools wait on one): in a task, queue's own pure-Python one, on a virtual semaphore
        simple_queue = self._saved_simple_queue
        python_simple_queue = getattr(queue, "_PySimpleQueue", simple_queue)

        def make_simple_queue(*args, **kwargs):
            return (python_simple_queue if vt.in_task() else simple_queue)(*args, **kwargs)

        make_simple_queue.__name__ = "SimpleQueue"
        queue.SimpleQueue = make_simple_queue

    def uninstall(self) -> None:
        for name, original in self._saved.items():
            setattr(threading, name, original)
        threading.Thread.start, threading.Thread.join, threading.Thread.is_alive = self._saved_methods
        if self._saved_queue_time is not None:
            queue.time = self._saved_queue_time
        queue.SimpleQueue = self._saved_simple_queue

    # -------------------------------------------------------------- threads
    def as_main_thread(self, body: Callable[[], None]) -> Callable[[], None]:
        """body, run as the program's main thread: threading.current_thread() is a non-daemon
        'MainThread' in it, so the threads it starts are non-daemon by default, as in Python."""

        def main() -> None:
            thread = _ProgramMainThread()
            try:
                body()
            finally:
                with threading._active_limbo_lock:
                    threading._active.pop(thread.ident, None)

        return main

    def start(self, thread: threading.Thread) -> None:
        if not thread._initialized:
            raise RuntimeError("thread.__init__() not called")
        if thread._started.is_set() or thread in self.tasks:
            raise RuntimeError("threads can only be started once")
        current = self.scheduler.task_for_thread()
        run = thread.run

        def run_until_over() -> None:
            try:
                run()
            except RunOver:  # the run ended while the thread ran: no error of the thread's
                pass

        thread.run = run_until_over
        with threading._active_limbo_lock:
            threading._limbo[thread] = thread
        self.tasks[thread] = self.scheduler.spawn(
            f"{current.name}-{thread.name}",
            current.owner,
            thread._bootstrap,
            self.start_thread,
            main=not thread.daemon,
        )
        thread._started.wait()  # the new task runs up to run() before this one goes on

    def join(self, thread: threading.Thread, timeout: float | None = None) -> None:
        if thread is threading.current_thread():
            raise RuntimeError("cannot join current thread")
        task = self.tasks[thread]
        if not task.done:
            self.scheduler.block(task.joiners, self._us(timeout))


class VLock:
    """threading.Lock in virtual time."""

    def __init__(self, vt: VirtualThreads) -> None:
        self._s = vt.scheduler
        self._vt = vt
        self._locked = False
        self._waiters: list = []

    def acquire(self, blocking: bool = True, timeout: float = -1) -> bool:
        if not self._locked:
            self._locked = True
            return True
        if not blocking:
            return False
        deadline = None if timeout is None or timeout < 0 else self._s.now_us + self._vt._us(timeout)
        while self._locked:
            left = None if deadline is None else deadline - self._s.now_us
            if left is not None and left <= 0:
                return False
            self._s.block(self._waiters, left)
        self._locked = True
        return True

    def release(self) -> None:
        if not self._locked:
            raise RuntimeError("release unlocked lock")
        self._locked = False
        self._s.wake(self._waiters, 1)

    def locked(self) -> bool:
        return self._locked

    __enter__ = acquire

    def __exit__(self, *exc) -> None:
        self.release()

    # what threading.Condition needs of a lock
    def _is_owned(self) -> bool:
        return self._locked

    def _release_save(self):
        self.release()

    def _acquire_restore(self, state) -> None:
        self.acquire()

    def _at_fork_reinit(self) -> None:
        """(what os.register_at_fork is given by concurrent.futures and logging: unlocked, no waiter)"""
        self._locked = False
        self._waiters = []


class VRLock(VLock):
    """threading.RLock in virtual time: the owning task may take it again."""

    def __init__(self, vt: VirtualThreads) -> None:
        super().__init__(vt)
        self._owner = None
        self._count = 0

    def acquire(self, blocking: bool = True, timeout: float = -1) -> bool:
        me = self._s.current
        if self._owner is me:
            self._count += 1
            return True
        if not super().acquire(blocking, timeout):
            return False
        self._owner, self._count = me, 1
        return True

    __enter__ = acquire

    def release(self) -> None:
        if self._owner is not self._s.current:
            raise RuntimeError("cannot release un-acquired lock")
        self._count -= 1
        if self._count == 0:
            self._owner = None
            super().release()

    def _is_owned(self) -> bool:
        return self._owner is self._s.current

    def _release_save(self):
        state = (self._owner, self._count)
        self._count = 1
        self.release()
        return state

    def _acquire_restore(self, state) -> None:
        self.acquire()
        self._owner, self._count = state

    def _at_fork_reinit(self) -> None:
        super()._at_fork_reinit()
        self._owner, self._count = None, 0


class VCondition:
    """threading.Condition in virtual time."""

    def __init__(self, vt: VirtualThreads, lock=None) -> None:
        self._vt = vt
        self._s = vt.scheduler
        self._lock = lock if lock is not None else VRLock(vt)
        self.acquire = self._lock.acquire
        self.release = self._lock.release
        self._waiters: list = []

    def __enter__(self):
        return self._lock.__enter__()

    def __exit__(self, *exc):
        return self._lock.__exit__(*exc)

    def wait(self, timeout: float | None = None) -> bool:
        if not self._lock._is_owned():
            raise RuntimeError("cannot wait on un-acquired lock")
        state = self._lock._release_save()
        try:
            return self._s.block(self._waiters, self._vt._us(timeout))
        finally:
            self._lock._acquire_restore(state)

    def wait_for(self, predicate: Callable[[], bool], timeout: float | None = None):
        end = None if timeout is None else self._s.now_us + self._vt._us(timeout)
        result = predicate()
        while not result:
            if end is not None:
                left = end - self._s.now_us
                if left <= 0:
                    break
                self.wait(left / 1e6)
            else:
                self.wait()
            result = predicate()
        return result

    def notify(self, n: int = 1) -> None:
        if not self._lock._is_owned():
            raise RuntimeError("cannot notify on un-acquired lock")
        self._s.wake(self._waiters, n)

    def notify_all(self) -> None:
        self.notify(len(self._waiters))

    notifyAll = notify_all  # noqa: N815 - threading's old name


class VEvent:
    """threading.Event in virtual time."""

    def __init__(self, vt: VirtualThreads) -> None:
        self._vt = vt
        self._s = vt.scheduler
        self._flag = False
        self._waiters: list = []

    def is_set(self) -> bool:
        return self._flag

    isSet = is_set  # noqa: N815 - threading's old name

    def set(self) -> None:
        self._flag = True
        self._s.wake(self._waiters)

    def clear(self) -> None:
        self._flag = False

    def wait(self, timeout: float | None = None) -> bool:
        if not self._flag:
            self._s.block(self._waiters, self._vt._us(timeout))
        return self._flag

    def _at_fork_reinit(self) -> None:
        """(threading calls it on each thread's events in a forked child: no waiter came along)"""
        self._waiters = []


class VSemaphore:
    """threading.Semaphore in virtual time."""

    def __init__(self, vt: VirtualThreads, value: int = 1) -> None:
        if value < 0:
            raise ValueError("semaphore initial value must be >= 0")
        self._vt = vt
        self._s = vt.scheduler
        self._value = value
        self._waiters: list = []

    def acquire(self, blocking: bool = True, timeout: float | None = None) -> bool:
        if not blocking and timeout is not None:
            raise ValueError("can't specify timeout for non-blocking acquire")
        deadline = None if timeout is None else self._s.now_us + self._vt._us(timeout)
        while self._value == 0:
            if not blocking:
                return False
            left = None if deadline is None else deadline - self._s.now_us
            if left is not None and left <= 0:
                return False
            self._s.block(self._waiters, left)
        self._value -= 1
        return True

    __enter__ = acquire

    def release(self, n: int = 1) -> None:
        if n < 1:
            raise ValueError("n must be one or more")
        self._value += n
        self._s.wake(self._waiters, n)

    def __exit__(self, *exc) -> None:
        self.release()


class VBoundedSemaphore(VSemaphore):
    """threading.BoundedSemaphore in virtual time."""

    def __init__(self, vt: VirtualThreads, value: int = 1) -> None:
        super().__init__(vt, value)
        self._initial = value

    def release(self, n: int = 1) -> None:
        if self._value + n > self._initial:
            raise ValueError("Semaphore released too many times")
        super().release(n)


class _ProgramMainThread(threading.Thread):
    """What threading.current_thread() is in a program's main task."""

    def __init__(self) -> None:
        super().__init__(name="MainThread", daemon=False)
        self._started.set()
        self._set_ident()
        with threading._active_limbo_lock:
            threading._active[self._ident] = self

    def is_alive(self) -> bool:
        return True
