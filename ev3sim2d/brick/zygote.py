"""A brick process that never runs a program: it loads the brick's code once and forks a brick per run.

A fresh brick spends about 75 ms of CPU starting Python and importing the
protocol, the brick runtime and the ev3dev2 shim; a class run starts a brick
for every submission in every variant.  A zygote (the name Android gives the
same idea) is started once, as a brick is (`boot.py zygote ...`, the same fixed
environment and interpreter flags), imports all of that, and then only waits
for requests.  Each request brings a new brick's file descriptors; the zygote
forks, and the child becomes that brick exactly as a fresh one would (its own
session, working folder, console, HOME and TMPDIR, the requester's cores), then
runs boot.run_brick: welcome, sandbox, program.  Forking costs about 7 ms.

Requests come on one SOCK_SEQPACKET socket (each message whole, so several
grading workers may share it), as {"scratch": folder, "cwd": working folder,
"memory": bool, "cpus": [...]} with the fds [connection, (shared memory,) console, reply].  The zygote
answers on the reply socket, which is the requester's alone: {"pid": pid} at
once, {"pid": pid, "status": wait status} when the brick has ended.  If the
requester goes away (its end of the reply socket closes) the zygote kills the
brick; when the request socket closes, it kills every brick left and ends.

Nothing of one run reaches the next: the zygote holds no program, no world and
no lesson (the requests hold only a folder name and fds), and every brick is a
child forked from the same untouched image.
"""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import sys

MAX_FDS = 4


class Zygote:
    def __init__(self, control_fd: int, root: str, run_brick) -> None:
        self.control = socket.socket(fileno=control_fd)
        self.root = root
        self.run_brick = run_brick
        self.replies: dict[int, socket.socket] = {}  # brick pid -> its requester's reply socket
        self.wake_r, self.wake_w = os.pipe()
        os.set_blocking(self.wake_w, False)
        signal.set_wakeup_fd(self.wake_w)
        signal.signal(signal.SIGCHLD, lambda *_: None)  # (the wake-up fd is what matters)

    def serve(self) -> int:
        while True:
            watched = [self.control, self.wake_r, *self.replies.values()]
            ready, _, _ = select.select(watched, [], [], 1.0)
            if self.wake_r in ready:
                os.read(self.wake_r, 4096)
            self._reap()
            for pid, reply in list(self.replies.items()):
                if reply in ready:  # the requester went away (or broke the rule of silence)
                    self._kill(pid)
            if self.control in ready:
                try:
                    message, fds, _, _ = socket.recv_fds(self.control, 4096, MAX_FDS)
                except OSError:
                    message, fds = b"", []
                if not message:
                    for fd in fds:
                        os.close(fd)
                    return self._end()
                self._spawn(message, fds)

    def _spawn(self, message: bytes, fds: list[int]) -> None:
        try:
            request = json.loads(message)
            memory = bool(request["memory"])
            if len(fds) != (4 if memory else 3):
                raise ValueError("wrong number of fds")
            conn, memory_fd, console, reply = fds if memory else (fds[0], -1, fds[1], fds[2])
            scratch, cpus = str(request["scratch"]), [int(c) for c in request.get("cpus") or ()]
            cwd = str(request.get("cwd") or scratch)
        except (ValueError, KeyError, TypeError):
            for fd in fds:
                os.close(fd)
            return
        sys.stdout.flush()
        sys.stderr.flush()
        pid = os.fork()
        if pid == 0:
            self._become_brick(conn, memory_fd, console, reply, scratch, cwd, cpus)
        for fd in (conn, memory_fd, console):
            if fd >= 0:
                os.close(fd)
        answer = socket.socket(fileno=reply)
        self.replies[pid] = answer
        try:
            answer.send(json.dumps({"pid": pid}).encode())
        except OSError:
            self._kill(pid)

    def _become_brick(
        self, conn: int, memory_fd: int, console: int, reply: int, scratch: str, cwd: str, cpus
    ) -> None:
        """In the child: look like a fresh brick (see simulator/bricks.py, start_brick), then be one."""
        code = 70
        try:
            signal.set_wakeup_fd(-1)
            signal.signal(signal.SIGCHLD, signal.SIG_DFL)
            for fd in (self.control.fileno(), self.wake_r, self.wake_w, reply):
                os.close(fd)
            for other in self.replies.values():
                os.close(other.fileno())
            os.setsid()
            if cpus and hasattr(os, "sched_setaffinity"):
                os.sched_setaffinity(0, cpus)
            os.chdir(cwd)
            os.environ["HOME"] = os.environ["TMPDIR"] = scratch
            null = os.open(os.devnull, os.O_RDONLY)
            os.dup2(null, 0)
            os.dup2(console, 1)
            os.dup2(console, 2)
            os.close(null)
            os.close(console)
            code = self.run_brick(conn, memory_fd, self.root)
            sys.stdout.flush()
        finally:
            os._exit(code)

    def _reap(self) -> None:
        while self.replies:
            try:
                pid, status = os.waitpid(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            reply = self.replies.pop(pid, None)
            if reply is not None:
                try:
                    reply.send(json.dumps({"pid": pid, "status": status}).encode())
                except OSError:
                    pass
                reply.close()

    def _kill(self, pid: int) -> None:
        for target in (lambda: os.killpg(pid, signal.SIGKILL), lambda: os.kill(pid, signal.SIGKILL)):
            try:
                target()
            except (ProcessLookupError, PermissionError):
                pass

    def _end(self) -> int:
        for pid in list(self.replies):
            self._kill(pid)
        for pid in list(self.replies):
            try:
                os.waitpid(pid, 0)
            except ChildProcessError:
                pass
        return 0


def serve(control_fd: int, root: str, run_brick) -> int:
    """The zygote's life, once everything a brick needs is imported (boot.py); run_brick(fd, memory_fd,
    root) is what a forked brick runs."""
    return Zygote(control_fd, root, run_brick).serve()
