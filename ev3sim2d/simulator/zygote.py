"""The simulator's end of a brick zygote (brick/zygote.py): started once, it forks a brick per run.

A class run starts a brick for every submission in every variant; started
fresh, each spends about 75 ms of CPU on Python and imports before its program,
forked from a zygote about 7 ms (benchmarks/grade.py).  The grader starts one
zygote before it forks its workers; each worker asks it for its brick
(`spawn`) over the one request socket they share, and gets a `ZygoteChild`,
which stands in for the subprocess.Popen of a fresh brick.  The brick is then
the zygote's child, not the worker's: the zygote reports how it ended, and
kills it if the worker goes away first.

The zygote is started like a brick (the same interpreter flags, the same fixed
environment, a session of its own) and holds nothing of the grader's: no
lesson, no hidden variant, no result, only the brick's own code.
"""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import subprocess
import sys
from pathlib import Path

from .bricks import BOOT, PACKAGE_DIR, PYTHON_P, _running, brick_environment, shim_root, site_packages

START_TIMEOUT_S = 30.0


class ZygoteGone(RuntimeError):
    """The zygote no longer answers: start bricks afresh."""


class ZygoteChild:
    """A brick forked by the zygote: what a run needs of its subprocess.Popen (pid, poll, wait, kill)."""

    def __init__(self, pid: int, reply: socket.socket) -> None:
        self.pid = pid
        self.returncode: int | None = None
        self._reply = reply

    def poll(self) -> int | None:
        self._read(0.0)
        return self.returncode

    def wait(self, timeout: float | None = None) -> int:
        self._read(timeout)
        if self.returncode is None:
            raise subprocess.TimeoutExpired(f"brick {self.pid}", timeout or 0.0)
        return self.returncode

    def kill(self) -> None:
        try:
            os.kill(self.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError):
            pass

    def _read(self, timeout: float | None) -> None:
        """Take the zygote's word on how the brick ended, waiting up to timeout for it."""
        if self.returncode is not None:
            return
        ready, _, _ = select.select([self._reply], [], [], timeout)
        if not ready:
            return
        try:
            data = self._reply.recv(4096)
            code = os.waitstatus_to_exitcode(json.loads(data)["status"]) if data else None
        except (OSError, ValueError, KeyError, TypeError):
            code = None
        # no word: the zygote is gone, and its bricks with it (they die with their parent)
        self.returncode = -signal.SIGKILL if code is None else code
        self._reply.close()


class BrickZygote:
    """A zygote process and the socket its bricks are asked for on (shared by forked workers)."""

    def __init__(self) -> None:
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        argv = [sys.executable, "-s", "-S", "-B", *PYTHON_P, str(BOOT), "zygote", str(theirs.fileno())]
        argv += [str(PACKAGE_DIR.parent), str(shim_root()), json.dumps(site_packages())]
        self.popen = subprocess.Popen(
            argv,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            cwd="/",
            env=brick_environment(Path("/nonexistent")),  # each brick gets its own scratch folder
            pass_fds=[theirs.fileno()],
            start_new_session=True,
        )
        theirs.close()
        self.control = ours
        _running.add(self.popen.pid)  # not an orphan for kill_orphans to end

    @property
    def pid(self) -> int:
        return self.popen.pid

    def spawn(
        self, scratch: Path, conn_fd: int, memory_fd: int, console_fd: int, cwd: Path | None = None
    ) -> ZygoteChild:
        """A new brick on these fds, with its scratch folder, working in cwd (default: scratch), on
        this process's cores; ZygoteGone if none."""
        mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            cpus = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else []
            request = {
                "scratch": str(scratch),
                "cwd": str(cwd or scratch),
                "memory": memory_fd >= 0,
                "cpus": cpus,
            }
            request = json.dumps(request).encode()
            fds = [conn_fd, *([memory_fd] if memory_fd >= 0 else []), console_fd, theirs.fileno()]
            try:
                socket.send_fds(self.control, [request], fds)
            except OSError as err:
                raise ZygoteGone(f"the brick zygote is gone ({err})") from None
        finally:
            theirs.close()
        ready, _, _ = select.select([mine], [], [], START_TIMEOUT_S)
        try:
            data = mine.recv(4096) if ready else b""
            pid = int(json.loads(data)["pid"]) if data else None
        except (OSError, ValueError, KeyError, TypeError):
            pid = None
        if pid is None:
            mine.close()
            raise ZygoteGone("the brick zygote did not answer")
        return ZygoteChild(pid, mine)

    def close(self) -> None:
        """End the zygote (it kills any brick still running) and reap it."""
        try:
            self.control.close()
        except OSError:
            pass
        try:
            self.popen.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.popen.kill()
            self.popen.wait()
        _running.discard(self.popen.pid)
