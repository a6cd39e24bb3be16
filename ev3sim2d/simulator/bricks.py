"""Starting a brick process on this computer, and making sure nothing of it outlives the run.

A brick is a fresh Python interpreter (`python -s -S -B -P ev3sim2d/brick/boot.py`)
with one end of a socket pair (and shared memory for the messages, where the
machine allows: protocol/shared_memory.py), a scratch folder of its own (its working folder,
HOME and TMPDIR), its console (fds 1 and 2) in a file of that folder, and a
short fixed environment: nothing of the caller's environment (tokens, the
hidden variants' location, PYTHONHASHSEED=random) reaches the program.  The
brick puts itself in its sandbox (ev3sim2d/brick/sandbox.py) before it reads
the program; the simulator tells it what it may read.

At the end the brick is killed with everything it started: its own PID
namespace ends with it; where the kernel gives none, the simulator, a child
subreaper (PR_SET_CHILD_SUBREAPER), inherits the orphans a program left and
kills them (`kill_orphans`).
"""

from __future__ import annotations

import compileall
import ctypes
import os
import select
import shutil
import signal
import site
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from ..protocol import PROTOCOL, Channel, SharedChannel
from ..protocol.shared_memory import available as shared_memory_available
from ..protocol.shared_memory import create_memory

PACKAGE_DIR = Path(__file__).resolve().parent.parent  # ev3sim2d/
BOOT = PACKAGE_DIR / "brick" / "boot.py"
PR_SET_CHILD_SUBREAPER = 36
CONSOLE_FILE = "console.log"
KEEP_CONSOLE_BYTES = 4000
UNPRIVILEGED_UID = 65534
SPIN_S = 0.002  # how long a side spins before it sleeps: waking a sleeper costs about 100 us here
_compiled = False
_running: set[int] = set()  # pids of the bricks this process runs now
_brick_sessions: set[int] = set()  # the sessions of every brick this process started (each leads its own)
_subreaper_since: int | None = None  # when this process became a subreaper (clock ticks since boot)


@dataclass
class BrickLimits:
    """What one brick may use (its program's CPU time, memory, file sizes, processes)."""

    cpu_s: int = 600
    memory_mb: int = 1024
    file_mb: int = 64
    processes: int = 64


@dataclass
class BrickProcess:
    """A running brick: its process, the simulator's end of its connection, its scratch folder."""

    popen: subprocess.Popen  # (or a zygote.ZygoteChild, which behaves like one)
    channel: Channel
    scratch: Path
    console: Path
    console_text: str = ""  # the end of the brick's console, read when it is stopped

    def stop(self, patience_s: float = 0.0) -> None:
        """Kill the brick and everything it started, reap it, remove its scratch folder.

        patience_s: how long a brick that is ending anyway (it said so, or its connection is gone)
        may take to end by itself, so that its exit status says how it ended."""
        self.channel.close()
        if patience_s > 0:
            _wait_for_exit(self.popen, patience_s)
        try:
            os.killpg(self.popen.pid, signal.SIGKILL)
        except (ProcessLookupError, PermissionError, OSError):
            pass
        try:
            self.popen.kill()
        except OSError:
            pass
        try:
            self.popen.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass  # a process that SIGKILL does not end: nothing more to do (its group was killed too)
        _running.discard(self.popen.pid)
        kill_orphans()
        self.console_text = console_tail(self.console)
        shutil.rmtree(self.scratch, ignore_errors=True)

    def ended_by_signal(self) -> str | None:
        code = self.popen.returncode
        if code is not None and code < 0:
            try:
                return signal.Signals(-code).name
            except ValueError:
                return f"signal {-code}"
        return None


def _wait_for_exit(popen: subprocess.Popen, timeout_s: float) -> None:
    """Wait up to timeout_s for the process to end, and notice at once when it does (Popen.wait with a
    timeout polls, sleeping up to 16 ms too long for a brick that ends within a few)."""
    try:
        fd = os.pidfd_open(popen.pid)
    except (AttributeError, OSError):  # not Linux >= 5.3, or the process is gone already
        fd = None
    if fd is not None:
        try:
            select.select([fd], [], [], timeout_s)
        finally:
            os.close(fd)
    try:
        popen.wait(timeout=0 if fd is not None else timeout_s)
    except subprocess.TimeoutExpired:
        pass


def shim_root() -> Path:
    """The folder that holds our `ev3dev2` package (installed copy first, then the source tree)."""
    for root in (PACKAGE_DIR / "_shim", PACKAGE_DIR.parent):
        if (root / "ev3dev2" / "__init__.py").exists():
            return root
    raise RuntimeError(f"ev3sim2d is incomplete: no ev3dev2 shim next to {PACKAGE_DIR}")


def site_packages() -> list[str]:
    """Where this interpreter finds third-party packages (numpy, Pillow), for the brick's sys.path."""
    found = []
    for path in [*site.getsitepackages(), site.getusersitepackages(), *sys.path]:
        if path and path.rstrip("/").endswith("-packages") and os.path.isdir(path) and path not in found:
            found.append(path)
    return found


def compile_brick_code() -> None:
    """Bytecode for the brick's code and the shim, so that no brick compiles them (bricks write none);
    once per process (a grader does it before it forks its workers)."""
    global _compiled
    if _compiled:
        return
    _compiled = True
    for folder in (PACKAGE_DIR / "brick", PACKAGE_DIR / "protocol", shim_root() / "ev3dev2"):
        try:
            compileall.compile_dir(str(folder), quiet=2)
        except OSError:
            pass
    try:
        compileall.compile_file(str(PACKAGE_DIR / "__init__.py"), quiet=2)
    except OSError:
        pass


def become_subreaper() -> bool:
    """Make this process the one that inherits orphans of its descendants (Linux), so it can end them."""
    global _subreaper_since
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        done = libc.prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False
    if done and _subreaper_since is None:
        _subreaper_since = _boot_ticks_now()
    return done


def _boot_ticks_now() -> int:
    """Now, in the clock ticks since boot that /proc/PID/stat gives a process's start time in."""
    return int(time.clock_gettime(time.CLOCK_BOOTTIME) * os.sysconf("SC_CLK_TCK"))


def _is_subreaper() -> bool:
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        value = ctypes.c_int(0)
        return libc.prctl(37, ctypes.byref(value), 0, 0, 0) == 0 and value.value == 1
    except (OSError, AttributeError):
        return False


def kill_orphans(keep: set[int] | frozenset = frozenset(), everything: bool = False) -> int:
    """As a subreaper: kill and reap every child process no one started on purpose (a brick's orphans).

    An orphan is a child of this process in a brick's session: a brick leads a session of its own,
    and its sandbox forbids setsid and setpgid, so nothing a program forks leaves it.  Children in
    `keep`, bricks still running, processes started before this process became a subreaper, and
    every child of another session (a browser the live page opened, a test runner's helpers) are
    left alone.  everything: kill every child started since, whatever its session (the grader, whose
    bricks run in its workers, and whose only children are those workers and the zygote)."""
    if not _is_subreaper() or _subreaper_since is None:
        return 0
    me = os.getpid()
    mine = _running | set(keep)
    killed = 0
    try:
        entries = os.listdir("/proc")
    except OSError:
        return 0
    for entry in entries:
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat", "rb") as f:
                stat = f.read().decode("latin-1")
        except OSError:
            continue
        fields = stat[stat.rfind(")") + 2 :].split()
        if len(fields) < 20 or int(fields[1]) != me or int(entry) in mine:
            continue
        if not everything and int(fields[3]) not in _brick_sessions:  # (state, ppid, pgrp, session, ...)
            continue
        if int(fields[19]) >= _subreaper_since:  # started since: a brick's, orphaned
            try:
                os.kill(int(entry), signal.SIGKILL)
                os.waitpid(int(entry), 0)
                killed += 1
            except (ProcessLookupError, ChildProcessError, PermissionError):
                pass
    return killed


def brick_environment(scratch: Path) -> dict[str, str]:
    """The whole environment a brick gets: the same on every machine, no secrets of the caller's."""
    return {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": str(scratch),
        "TMPDIR": str(scratch),
        "LANG": "C.UTF-8",
        "LC_ALL": "C.UTF-8",
        "TZ": "UTC",
        "PYTHONHASHSEED": "0",
        "PYTHONIOENCODING": "utf-8",
        "PYTHONDONTWRITEBYTECODE": "1",
        "OPENBLAS_NUM_THREADS": "1",  # numpy's BLAS: one thread, in the brick's share of the machine
        "OMP_NUM_THREADS": "1",
    }


def start_brick(
    readable: list[Path],
    shared_memory: bool = True,
    scratch_in: Path | None = None,
    spin: bool = True,
    zygote=None,
) -> tuple[BrickProcess, list[str]]:
    """Start a brick process; returns it and the paths its sandbox must let it read (besides the system's).

    scratch_in: the folder to make the brick's scratch folder in (default: the system's temporary
    folder); a grading worker uses its job folder, which the grader removes even if the worker is
    killed.  spin: whether the two sides may spin while they wait for each other (not when other runs
    share the machine's cores: see protocol/shared_memory.py).  zygote: a BrickZygote to fork the brick
    from (zygote.py); a fresh process when it is None or gone."""
    compile_brick_code()
    scratch = Path(tempfile.mkdtemp(prefix="ev3sim2d-brick-", dir=scratch_in))
    if os.geteuid() == 0:
        os.chown(scratch, UNPRIVILEGED_UID, UNPRIVILEGED_UID)  # the brick gives up root before it writes
        if scratch_in is not None:
            _let_through(Path(scratch_in))
    console = scratch / CONSOLE_FILE
    ours, theirs = socket.socketpair()
    memory_fd = create_memory() if shared_memory and shared_memory_available() else -1
    passed = [theirs.fileno()] + ([memory_fd] if memory_fd >= 0 else [])
    argv = [sys.executable, "-s", "-S", "-B", "-P", str(BOOT), str(theirs.fileno()), str(memory_fd)]
    with open(console, "wb") as out:
        popen = None
        if zygote is not None:
            try:
                popen = zygote.spawn(scratch, theirs.fileno(), memory_fd, out.fileno())
            except RuntimeError:  # ZygoteGone
                popen = None
        if popen is None:
            popen = subprocess.Popen(
                [*argv, str(PACKAGE_DIR.parent)],
                stdin=subprocess.DEVNULL,
                stdout=out,
                stderr=out,
                cwd=scratch,
                env=brick_environment(scratch),
                pass_fds=passed,
                start_new_session=True,
            )
    theirs.close()
    _running.add(popen.pid)
    _brick_sessions.add(popen.pid)
    if memory_fd >= 0:
        channel = SharedChannel(ours, os.dup(memory_fd), simulator=True, spin_s=SPIN_S if spin else 0.0)
        os.close(memory_fd)
    else:
        channel = Channel(ours, spin_s=SPIN_S if spin else 0.0)
    read_paths = [str(shim_root() / "ev3dev2"), *(str(p) for p in readable)]
    return BrickProcess(popen, channel, scratch, console), read_paths


def brick_welcome(
    brick: BrickProcess,
    read_paths: list[str],
    program: Path,
    robot: str,
    tick_us: int,
    seed: int,
    limits: BrickLimits,
    sandbox: bool = True,
) -> list:
    """The welcome a brick started here gets: its robot's name, the clock, the seed, its program, and
    the sandbox it must enter (what it may read and write, its limits; None: no sandbox)."""
    return [
        "welcome",
        {
            "protocol": PROTOCOL,
            "robot": robot,
            "tick_us": tick_us,
            "seed": seed,
            "program": str(program),
            "program_dirs": [str(program.parent)],
            "shim_root": str(shim_root()),
            "site_packages": site_packages(),
            "sandbox": {
                "read_paths": read_paths,
                "write_paths": [str(brick.scratch)],
                "cpu_s": limits.cpu_s,
                "memory_mb": limits.memory_mb,
                "file_mb": limits.file_mb,
                "processes": limits.processes,
            }
            if sandbox
            else None,
        },
    ]


def _let_through(folder: Path) -> None:
    """Let the brick's unprivileged user pass through the folders above its scratch folder (not list
    or read them: its sandbox still allows nothing there)."""
    for part in [folder, *folder.parents]:
        try:
            mode = part.stat().st_mode
            if not mode & 0o001:
                os.chmod(part, mode | 0o001)
        except OSError:
            return
        if part == Path(tempfile.gettempdir()):
            return


def console_tail(path: Path, keep_bytes: int = KEEP_CONSOLE_BYTES) -> str:
    """The end of what a process wrote to its console file (a crash's message)."""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            size = f.tell()
            f.seek(max(0, size - keep_bytes))
            return f.read().decode("utf-8", "replace").strip()
    except OSError:
        return ""
