"""A brick's processes, together, within its memory budget: a watchdog where the system shows them.

A brick's own limit (RLIMIT_AS) is per process, and a program may start as many processes as its
process limit lets it: four children held 1.8 GB against a 512 MB limit.  So, where /proc shows every
process, a thread of the simulator's looks at each brick's processes every WATCH_S: the brick's own,
its descendants, and whatever stayed in its sessions (an orphan that left the tree), and adds up what
they really use (their proportional set size: shared pages once, not once per process).  When a
brick's processes use more than its budget and START_ALLOWANCE_MB (its interpreter and the shim)
together, every one of them is killed, and the run says the program ran out of memory.  (Windows limits a brick's processes together
with its Job Object; elsewhere only the per-process limit holds: docs/platforms.md.)
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading

WATCH_S = 0.2
START_ALLOWANCE_MB = 64
_PAGE = os.sysconf("SC_PAGE_SIZE") if hasattr(os, "sysconf") else 4096
_lock = threading.Lock()
_watched: dict[int, Watched] = {}  # brick pid -> what is known of it
_thread: threading.Thread | None = None


class Watched:
    """One brick: what its processes may use together, and whether they went over."""

    def __init__(self, pid: int, budget_mb: int) -> None:
        self.pid = pid
        self.budget = (budget_mb + START_ALLOWANCE_MB) * 2**20
        self.over_bytes: int | None = None  # what its processes used when they were killed


def available() -> bool:
    return os.path.isdir("/proc/self") and hasattr(os, "kill") and hasattr(signal, "SIGKILL")


def watch(pid: int, budget_mb: int) -> Watched | None:
    """Watch the brick whose process is pid; None where processes cannot be watched."""
    global _thread
    if not available():
        return None
    watched = Watched(pid, budget_mb)
    with _lock:
        _watched[pid] = watched
        if _thread is None:
            _thread = threading.Thread(target=_run, name="ev3sim2d-memory-watch", daemon=True)
            _thread.start()
    return watched


def unwatch(pid: int) -> None:
    with _lock:
        _watched.pop(pid, None)


def _run() -> None:
    global _thread
    stop = threading.Event()
    while not stop.wait(WATCH_S):
        with _lock:
            bricks = list(_watched.values())
            if not bricks:
                _thread = None
                return
        with contextlib.suppress(OSError):
            _look(bricks)


def _look(bricks: list[Watched]) -> None:
    table = _processes()
    for brick in bricks:
        pids = _brick_processes(brick.pid, table)
        used = sum(_memory(pid) for pid in pids)
        if used > brick.budget:
            brick.over_bytes = used
            for pid in pids:
                with contextlib.suppress(OSError):
                    os.kill(pid, signal.SIGKILL)


def _processes() -> dict[int, tuple[int, int]]:
    """pid -> (parent pid, session id), for every process /proc shows."""
    table = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat", "rb") as f:
                    stat = f.read().decode("latin-1")
            except OSError:
                continue
            fields = stat[stat.rfind(")") + 2 :].split()  # (state, ppid, pgrp, session, ...)
            table[int(name)] = (int(fields[1]), int(fields[3]))
    return table


def _brick_processes(pid: int, table: dict[int, tuple[int, int]]) -> list[int]:
    """The brick's process, its descendants, and every process of their sessions."""
    if pid not in table:
        return []
    children: dict[int, list[int]] = {}
    for child, (parent, _) in table.items():
        children.setdefault(parent, []).append(child)
    found, stack = {pid}, [pid]
    while stack:
        for child in children.get(stack.pop(), ()):
            if child not in found:
                found.add(child)
                stack.append(child)
    sessions = {table[p][1] for p in found if p in table}
    found |= {p for p, (_, session) in table.items() if session in sessions and session > 1}
    return sorted(found)


def _memory(pid: int) -> int:
    """What a process really uses: its proportional set size (resident size where that is not shown)."""
    try:
        with open(f"/proc/{pid}/smaps_rollup", "rb") as f:
            for line in f:
                if line.startswith(b"Pss:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError):
        pass
    try:
        with open(f"/proc/{pid}/statm", "rb") as f:
            return int(f.read().split()[1]) * _PAGE
    except (OSError, ValueError, IndexError):
        return 0
