"""Starting a brick process on this computer, and making sure nothing of it outlives the run.

A brick is a fresh Python interpreter (`python -s -S -B -P ev3sim2d/brick/boot.py`)
with one end of a socket pair (and shared memory for the messages, where the
machine allows: protocol/shared_memory.py), a scratch folder of its own (HOME and TMPDIR,
holding a copy of the program's folder that is its working folder: working_folder.py), its
console (fds 1 and 2) in a file of that folder, and a
short fixed environment: nothing of the caller's environment (tokens, the
hidden variants' location, PYTHONHASHSEED=random) reaches the program.  The
brick puts itself in its sandbox (ev3sim2d/brick/sandbox.py) before it reads
the program; the simulator tells it what it may read.

Where a socket cannot be handed to a new process (no fork, no Unix socket pair: Windows), or
where EV3SIM2D_PORTABLE=1 asks for it (to test that way on Linux), the brick connects over
loopback TCP instead and proves itself with a one-time token (protocol/loopback.py); there is
no shared memory and no zygote then.  What the system offers from outside is added where it
exists: a Job Object (Windows: job_object.py) and sandbox-exec (macOS: sandbox_exec.py).

At the end the brick is killed with everything it started: its own PID
namespace ends with it; where the kernel gives none, the simulator, a child
subreaper (PR_SET_CHILD_SUBREAPER), inherits the orphans a program left and
kills them (`kill_orphans`); on Windows, closing its Job Object ends every process in it.
"""

from __future__ import annotations

import compileall
import ctypes
import os
import select
import signal
import site
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from ..protocol import PROTOCOL, Channel, SharedChannel
from ..protocol.loopback import LoopbackListener
from ..protocol.shared_memory import available as shared_memory_available
from ..protocol.shared_memory import create_memory
from ..protocol.stream import send_timeout
from . import job_object, memory_watch, sandbox_exec
from .scratch import open_console, remove_tree, tail
from .working_folder import WorkingFolder, keep_written, make_working_folder

PACKAGE_DIR = Path(__file__).resolve().parent.parent  # ev3sim2d/
BOOT = PACKAGE_DIR / "brick" / "boot.py"
PR_SET_CHILD_SUBREAPER = 36
CONSOLE_FILE = "console.log"
KEEP_CONSOLE_BYTES = 4000
UNPRIVILEGED_UID = 65534
PYTHON_P = ["-P"] if sys.version_info >= (3, 11) else []  # (boot.py takes its own folder off sys.path too)
SPIN_S = 0.002  # how long a side spins before it sleeps: waking a sleeper costs about 100 us here
START_TIMEOUT_S = 60.0  # a brick on loopback TCP must connect within this much real time
SEND_TIMEOUT_S = 10.0  # a brick that takes nothing the simulator sends for this long is dropped
PORTABLE = "EV3SIM2D_PORTABLE"
# EV3SIM2D_EVERY_TICK=1: every brick hears of every tick it waits through, as before quiet waits (protocol 2's
# "u"): the same run, fingerprint for fingerprint, for tests and benchmarks to compare.
EVERY_TICK = "EV3SIM2D_EVERY_TICK"
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


def portable() -> bool:
    """Whether bricks start as they must where a socket cannot be handed to a new process (no fork,
    no Unix socket pair), or as EV3SIM2D_PORTABLE=1 asks: over loopback TCP, without shared memory."""
    return os.environ.get(PORTABLE) == "1" or not (hasattr(os, "fork") and hasattr(socket, "AF_UNIX"))


@dataclass
class BrickProcess:
    """A running brick: its process, the simulator's end of its connection, its scratch folder."""

    popen: subprocess.Popen  # (or a zygote.ZygoteChild, which behaves like one)
    channel: Channel
    scratch: Path
    console: int  # the descriptor of its console file, opened here before it started (scratch.py)
    console_text: str = ""  # the end of the brick's console, read when it is stopped
    job: job_object.JobObject | None = None  # (Windows) the Job Object every process of the brick is in
    memory: memory_watch.Watched | None = None  # its processes' memory together, where /proc shows them
    outside: dict = field(default_factory=dict)  # isolation layers put around it from outside: name -> state
    working: WorkingFolder | None = None  # the copy of the program's folder it works in
    keep_written: bool = False  # keep what its program wrote beside itself (working_folder.keep_written)
    kept: tuple[list[str], list[str]] = ([], [])  # (files kept, files not kept and why) once it stopped

    def stop(self, patience_s: float = 0.0) -> None:
        """Kill the brick and everything it started, reap it, remove its scratch folder.

        patience_s: how long a brick that is ending anyway (it said so, or its connection is gone)
        may take to end by itself, so that its exit status says how it ended."""
        self.channel.close()
        memory_watch.unwatch(self.popen.pid)
        if patience_s > 0:
            _wait_for_exit(self.popen, patience_s)
        if hasattr(os, "killpg"):
            try:
                os.killpg(self.popen.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError, OSError):
                pass
        try:
            self.popen.kill()
        except OSError:
            pass
        if self.job is not None:
            self.job.close()  # every process the brick started ends with it
        try:
            self.popen.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass  # a process that SIGKILL does not end: nothing more to do (its group was killed too)
        _running.discard(self.popen.pid)
        kill_orphans()
        self.console_text = tail(self.console, KEEP_CONSOLE_BYTES)
        os.close(self.console)
        if self.keep_written and self.working is not None:
            self.kept = keep_written(self.working)
        _remove(self.scratch)

    def ended_by_signal(self) -> str | None:
        code = self.popen.returncode
        if code is not None and code < 0:
            try:
                return signal.Signals(-code).name
            except ValueError:
                return f"signal {-code}"
        return None

    def limit_at_end(self) -> str | None:
        """The limit the brick was ended at from outside: its processes' memory together (memory_watch),
        a Job Object's CPU time (Windows says so by the exit code), else None."""
        if self.memory is not None and self.memory.over_bytes is not None:
            return "memory"
        if self.job is not None and self.popen.returncode == job_object.CPU_LIMIT_EXIT_CODE:
            return "cpu"
        return None


def _remove(folder: Path, patience_s: float = 2.0) -> None:
    """Remove a scratch folder; where files of a process still ending cannot be removed yet (Windows),
    try again for a while."""
    end = time.monotonic() + patience_s
    while True:
        remove_tree(folder)
        if not os.path.lexists(folder) or time.monotonic() > end:
            return
        time.sleep(0.05)


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


SHIMS = ("ev3dev2", "pybricks")  # the APIs a brick's program may import (brick/program_kind.py)


def shim_root() -> Path:
    """The folder that holds our `ev3dev2` and `pybricks` packages (installed copy first, then the source
    tree)."""
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
    for folder in (PACKAGE_DIR / "brick", PACKAGE_DIR / "protocol", *(shim_root() / s for s in SHIMS)):
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
    except (OSError, AttributeError, TypeError):  # (TypeError: no C library by that name: Windows)
        return False
    if done and _subreaper_since is None:
        _subreaper_since = _boot_ticks_now()
    return done


def die_with_parent(parent: int) -> str:
    """End this process when its parent does, however the parent ends (SIGKILL too): the kernel's
    parent-death signal where it has one, else a thread that looks whether the parent is still the
    one it was (a POSIX system reparents an orphan); where neither exists (Windows) the parent's Job
    Object does it.  How, in words."""
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        if libc.prctl(1, signal.SIGKILL, 0, 0, 0) == 0:  # PR_SET_PDEATHSIG
            if os.getppid() != parent:  # it died before the signal was asked for
                os._exit(1)
            return "the kernel's parent-death signal"
    except (OSError, AttributeError, TypeError):
        pass
    if not hasattr(os, "getppid") or not hasattr(os, "setsid"):
        return "its parent's Job Object"

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(0.2)
        os._exit(1)

    threading.Thread(target=watch, name="ev3sim2d-parent-watch", daemon=True).start()
    return "a thread that watches its parent"


def _boot_ticks_now() -> int:
    """Now, in the clock ticks since boot that /proc/PID/stat gives a process's start time in."""
    return int(time.clock_gettime(time.CLOCK_BOOTTIME) * os.sysconf("SC_CLK_TCK"))


def _is_subreaper() -> bool:
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        value = ctypes.c_int(0)
        return libc.prctl(37, ctypes.byref(value), 0, 0, 0) == 0 and value.value == 1
    except (OSError, AttributeError, TypeError):
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
    """The whole environment a brick gets: the same on every machine, no secrets of the caller's.
    Where the system needs its own folder to start a process that uses sockets (Windows' SYSTEMROOT),
    that is passed on, and its temporary folder is the scratch folder."""
    environment = {
        "PATH": "/usr/local/bin:/usr/bin:/bin",
        "HOME": str(scratch),
        "TMPDIR": str(scratch),
        "LANG": "C.UTF-8",
        "LC_ALL": "C.UTF-8",
        "TZ": "UTC",
        "PYTHONHASHSEED": "0",
        "PYTHONIOENCODING": "utf-8",
        "PYTHONUTF8": "1",  # files opened without an encoding are UTF-8, as on the EV3, on every system
        "PYTHONDONTWRITEBYTECODE": "1",
        "OPENBLAS_NUM_THREADS": "1",  # numpy's BLAS: one thread, in the brick's share of the machine
        "OMP_NUM_THREADS": "1",
    }
    system_root = os.environ.get("SYSTEMROOT")
    if system_root:
        system32 = os.path.join(system_root, "System32")
        environment.update(
            SYSTEMROOT=system_root, TEMP=str(scratch), TMP=str(scratch), USERPROFILE=str(scratch)
        )
        environment["PATH"] = os.pathsep.join([os.path.dirname(sys.executable), system32, system_root])
    return environment


def start_brick(
    readable: list[Path],
    shared_memory: bool = True,
    scratch_in: Path | None = None,
    spin: bool = True,
    zygote=None,
    limits: BrickLimits | None = None,
    program: Path | None = None,
) -> tuple[BrickProcess, list[str]]:
    """Start a brick process; returns it and the paths its sandbox must let it read (besides the system's).

    scratch_in: the folder to make the brick's scratch folder in (default: the system's temporary
    folder); a grading worker uses its job folder, which the grader removes even if the worker is
    killed.  spin: whether the two sides may spin while they wait for each other (not when other runs
    share the machine's cores: see protocol/shared_memory.py).  zygote: a BrickZygote to fork the brick
    from (zygote.py); a fresh process when it is None or gone.  limits: what a Job Object (where the
    system has them) holds the brick's processes to, together; the brick sets its own limits too.
    program: the program the brick will run: what it may read is copied into its scratch folder and
    the brick works in the copy of the program's folder, as a brick works in the program's folder
    (working_folder.py); it then reads nothing of the originals.  None: it works in its scratch
    folder and may read `readable` where it is."""
    compile_brick_code()
    limits = limits or BrickLimits()
    scratch = Path(tempfile.mkdtemp(prefix="ev3sim2d-brick-", dir=scratch_in))
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        os.chown(scratch, UNPRIVILEGED_UID, UNPRIVILEGED_UID)  # the brick gives up root before it writes
        if scratch_in is not None:
            _let_through(Path(scratch_in))
    console = open_console(scratch / CONSOLE_FILE)  # (the program may replace the name, not this)
    try:
        working = None if program is None else make_working_folder(scratch, list(readable), program)
        if working is not None and hasattr(os, "geteuid") and os.geteuid() == 0:
            _hand_over(scratch)
        cwd = scratch if working is None else working.folder
        if portable():
            brick = _start_over_loopback(scratch, cwd, console, spin, limits)
        else:
            brick = _start_with_socket_pair(scratch, cwd, console, shared_memory, spin, zygote)
    except BaseException:
        os.close(console)
        raise
    brick.working = working
    _running.add(brick.popen.pid)
    _brick_sessions.add(brick.popen.pid)
    if brick.job is None:  # (a Job Object limits its processes' memory together itself)
        brick.memory = memory_watch.watch(brick.popen.pid, limits.memory_mb)
    originals = [str(p) for p in readable] if working is None else []
    return brick, [*(str(shim_root() / s) for s in SHIMS), *originals]


def _boot_argv(*arguments: str, scratch: Path) -> list[str]:
    """The brick's command line: the interpreter, our flags, boot.py; under sandbox-exec where it exists.
    Where bricks go in a Job Object (Windows), a virtual environment's python is a launcher that starts
    the real interpreter as a child of its own, which could escape the job: the real one is started."""
    interpreter = sys.executable
    if job_object.available():
        interpreter = getattr(sys, "_base_executable", None) or sys.executable
    argv = [interpreter, "-s", "-S", "-B", *PYTHON_P, str(BOOT), *arguments]
    return sandbox_exec.wrap(argv, [str(scratch)])


def _outside_layers(job: job_object.JobObject | None) -> dict:
    layers = {}
    if os.access(sandbox_exec.SANDBOX_EXEC, os.X_OK):  # (on, or off with the reason it refused)
        layers["sandbox_exec"] = sandbox_exec.describe()
    if job is not None:
        layers["job_object"] = job.describe()
    return layers


def _hand_over(scratch: Path) -> None:
    """Give the brick's unprivileged user what was copied into its scratch folder (it gives up root
    before it writes), without following a link."""
    for folder, folders, files in os.walk(scratch):
        for name in folders + files:
            os.lchown(os.path.join(folder, name), UNPRIVILEGED_UID, UNPRIVILEGED_UID)


def _start_with_socket_pair(scratch, cwd, console: int, shared_memory, spin, zygote) -> BrickProcess:
    """A brick given one end of a socket pair (and shared memory, where there is some) as inherited fds."""
    ours, theirs = socket.socketpair()
    memory_fd = create_memory() if shared_memory and shared_memory_available() else -1
    passed = [theirs.fileno()] + ([memory_fd] if memory_fd >= 0 else [])
    popen = None
    if zygote is not None:
        try:
            popen = zygote.spawn(scratch, theirs.fileno(), memory_fd, console, cwd=cwd)
        except RuntimeError:  # ZygoteGone
            popen = None
    if popen is None:
        popen = subprocess.Popen(
            _boot_argv(str(theirs.fileno()), str(memory_fd), str(PACKAGE_DIR.parent), scratch=scratch),
            stdin=subprocess.DEVNULL,
            stdout=console,
            stderr=console,
            cwd=cwd,
            env=brick_environment(scratch),
            pass_fds=passed,
            start_new_session=True,
        )
    theirs.close()
    if memory_fd >= 0:
        channel = SharedChannel(ours, os.dup(memory_fd), simulator=True, spin_s=SPIN_S if spin else 0.0)
        os.close(memory_fd)
    else:
        send_timeout(
            ours, SEND_TIMEOUT_S
        )  # (a brick that never reads its replies is dropped, not waited for)
        channel = Channel(ours, spin_s=SPIN_S if spin else 0.0)
    return BrickProcess(popen, channel, scratch, console, outside=_outside_layers(None))


def _start_over_loopback(scratch, cwd, console: int, spin, limits: BrickLimits) -> BrickProcess:
    """A brick that connects back over loopback TCP with the token it reads from its standard input,
    in a Job Object where the system has them (assigned before it hears a word from the simulator)."""
    listener = LoopbackListener()
    try:
        options: dict = {"start_new_session": True} if hasattr(os, "setsid") else {}
        popen = subprocess.Popen(
            _boot_argv("tcp", str(listener.port), str(PACKAGE_DIR.parent), scratch=scratch),
            stdin=subprocess.PIPE,
            stdout=console,
            stderr=console,
            cwd=cwd,
            env=brick_environment(scratch),
            **options,
        )
        job, outside = None, {}
        if job_object.available():
            try:
                job = job_object.JobObject(limits.memory_mb, limits.processes, limits.cpu_s)
                job.assign(popen)
            except OSError as err:
                if job is not None:
                    job.close()
                job, outside = None, {"job_object": f"off: {err}"}
        try:
            popen.stdin.write(listener.token.encode() + b"\n")
            popen.stdin.close()
        except OSError:
            pass  # it ended already: its console says why
        channel = listener.accept(START_TIMEOUT_S, lambda: popen.poll() is None, SPIN_S if spin else 0.0)
    finally:
        listener.close()
    if channel is None:  # it never connected: a channel that is gone, so the run says the brick did not start
        ours, theirs = socket.socketpair()
        theirs.close()
        channel = Channel(ours)
    send_timeout(channel.sock, SEND_TIMEOUT_S)  # (a brick that never reads its replies is dropped)
    outside.update(_outside_layers(job))
    return BrickProcess(popen, channel, scratch, console, job=job, outside=outside)


def brick_welcome(
    brick: BrickProcess,
    read_paths: list[str],
    program: Path,
    robot: str,
    tick_us: int,
    seed: int,
    limits: BrickLimits,
    sandbox: bool = True,
    arguments: Sequence[str] = (),
    debug: str | None = None,
) -> list:
    """The welcome a brick started here gets: its robot's name, the clock, the seed, its program, and
    the sandbox it must enter (what it may read and write, its limits; None: no sandbox).  Paths go as
    the brick names them (bricks_path); the program is its copy where the brick works in one.
    arguments: the program's own command line after its name (sys.argv[1:]); sys.argv[0] is the
    program's name, as `python3 prog.py ARG...` in its folder gives it on a brick.
    debug: None (breakpoint() does nothing, as in grading), "breakpoints" (it stops in the brick's
    debugger) or "start" (the program stops at its first line too): brick/debugger.py."""
    ran = program if brick.working is None else brick.working.program
    return [
        "welcome",
        {
            "protocol": PROTOCOL,
            "robot": robot,
            "tick_us": tick_us,
            "seed": seed,
            "program": bricks_path(ran),
            "program_dirs": [bricks_path(ran.parent)],
            "argv": [ran.name, *(str(a) for a in arguments)],
            "debug": debug,
            "quiet": os.environ.get(EVERY_TICK) != "1",
            "shim_root": bricks_path(shim_root()),
            "site_packages": [bricks_path(p) for p in site_packages()],
            "sandbox": {
                "read_paths": [bricks_path(p) for p in read_paths],
                "write_paths": [bricks_path(brick.scratch)],
                "cpu_s": limits.cpu_s,
                "memory_mb": limits.memory_mb,
                "file_mb": limits.file_mb,
                "processes": limits.processes,
            }
            if sandbox
            else None,
        },
    ]


def bricks_path(path: str | Path) -> str:
    """A path as the brick names it: the brick's file names are UTF-8 (brick_environment), this
    process's may not be (LC_ALL=C makes them ASCII, with the other bytes as surrogates), so the path
    goes as the bytes the system knows it by, read as UTF-8.  A name that is not UTF-8 at all cannot
    be sent as text: ProgramError says which and what to do."""
    from .program import ProgramError

    text = os.fsencode(path).decode("utf-8", "surrogateescape")
    if any("\udc80" <= ch <= "\udcff" for ch in text):
        raise ProgramError(
            f"{os.fsdecode(path)!r}: this file or folder name is not UTF-8 text; rename it with letters the "
            "system shows (e.g. save it again from the editor)"
        )
    return text


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
