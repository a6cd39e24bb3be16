"""The features of Linux's that some tests need and Windows or macOS lack, each checked by itself
(never by the system's name): what `@pytest.mark.needs_linux(...)` (tests/conftest.py) names.

A test that needs one is skipped where it is missing, with a reason that names it; on Linux every one
is there and every test runs.  Where a test only adapts (leaves a program out of a class run that
would otherwise harm the machine), it asks `missing(...)` itself.
"""

from __future__ import annotations

import functools
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time


def _importable(name: str) -> bool:
    try:
        __import__(name)
    except ImportError:
        return False
    return True


def _proc_lists_processes() -> bool:
    try:
        with open(f"/proc/{os.getpid()}/stat", "rb"):
            return True
    except OSError:
        return False


def _file_modes_kept() -> bool:
    """Whether chmod sets the mode bits it is given (POSIX), not only a read-only flag (Windows)."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "probe")
        with open(path, "wb"):
            pass
        os.chmod(path, 0o640)
        return os.stat(path).st_mode & 0o777 == 0o640


def _seqpacket_pairs() -> bool:
    """Whether a Unix socket pair of SOCK_SEQPACKET can be made (macOS has the name, not the pair) and
    can pass file descriptors."""
    if not all(hasattr(socket, name) for name in ("AF_UNIX", "SOCK_SEQPACKET", "send_fds")):
        return False
    try:
        pair = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    except OSError:
        return False
    for end in pair:
        end.close()
    return True


def _linux_kernel() -> bool:
    from ev3sim2d.brick.sandbox import linux_kernel

    return linux_kernel()


def _job_objects() -> bool:
    from ev3sim2d.simulator import job_object

    return job_object.available()


def _address_space_limit() -> bool:
    """Whether a process may limit its own memory (macOS refuses RLIMIT_AS), tried in a child."""
    if not _importable("resource"):
        return False
    trial = (
        "import resource\n"
        "hard = resource.getrlimit(resource.RLIMIT_AS)[1]\n"
        "limit = 1 << 40 if hard == resource.RLIM_INFINITY else hard\n"
        "resource.setrlimit(resource.RLIMIT_AS, (limit, limit))"
    )
    done = subprocess.run([sys.executable, "-c", trial], capture_output=True, timeout=60)
    return done.returncode == 0


def _in_a_temporary_folder(make) -> bool:
    """Whether make(folder) succeeds in a fresh temporary folder."""
    with tempfile.TemporaryDirectory() as folder:
        try:
            make(folder)
        except (OSError, NotImplementedError, ValueError):
            return False
    return True


def _symlink(folder: str) -> None:
    os.symlink(folder, os.path.join(folder, "link"))


def _any_file_name(folder: str) -> None:
    os.mkdir(os.path.join(folder, 'a "quoted" back\\slash\nand a new line'))


def _script(folder: str) -> None:
    path = os.path.join(folder, "script")
    with open(path, "w", encoding="utf-8") as f:
        f.write(f"#!{sys.executable}\nimport sys\nsys.exit(7)\n")
    os.chmod(path, 0o755)
    read, write = os.pipe()
    try:
        if subprocess.run([path], capture_output=True, timeout=60, pass_fds=[write]).returncode != 7:
            raise OSError("the script did not run")
    finally:
        os.close(read)
        os.close(write)


def _select_on_pipes() -> bool:
    """Whether select() takes a pipe (Windows' takes only sockets)."""
    read, write = os.pipe()
    try:
        os.write(write, b"x")
        return select.select([read], [], [], 0)[0] == [read]
    except OSError:
        return False
    finally:
        os.close(read)
        os.close(write)


def _posix_shell() -> bool:
    """Whether commands given to subprocess with shell=True are read by a POSIX shell (quotes, `#`
    comments, pipes), as the docs' commands are written, and not by cmd.exe."""
    done = subprocess.run("printf '%s' 'a b'  # a comment", shell=True, capture_output=True, timeout=60)
    return done.returncode == 0 and done.stdout == b"a b"


# name: (what a test needs, as its skip names it; whether this system has it)
FEATURES = {
    "fork": ("os.fork", lambda: hasattr(os, "fork")),
    "proc": ("/proc, the processes as the kernel lists them", _proc_lists_processes),
    "signals": (
        "POSIX signals (SIGKILL, SIGSEGV, SIGALRM ...: a process killed or crashed by one; os.kill, alarm)",
        lambda: hasattr(signal, "SIGKILL"),
    ),
    "unix_sockets": ("Unix socket pairs of SOCK_SEQPACKET that pass file descriptors", _seqpacket_pairs),
    "resource_limits": (
        "resource limits (the resource module: RLIMIT_FSIZE, RLIMIT_CPU, ...)",
        lambda: _importable("resource"),
    ),
    "memory_limit": (
        "memory limit on a process (RLIMIT_AS; on Windows a Job Object's)",
        lambda: _job_objects() or _address_space_limit(),
    ),
    "cpu_limit": (
        "CPU-time limit on a process (RLIMIT_CPU; on Windows a Job Object's)",
        lambda: _job_objects() or _importable("resource"),
    ),
    "file_modes": ("POSIX file modes (chmod sets rwx bits)", _file_modes_kept),
    "linux_kernel": (
        "kernel interfaces (prctl, namespaces, Landlock, seccomp: the full sandbox)",
        _linux_kernel,
    ),
    "symlinks": ("symbolic links any user may make (os.symlink)", lambda: _in_a_temporary_folder(_symlink)),
    "file_names": (
        'file names with any character but "/" (quotes, backslashes, new lines)',
        lambda: _in_a_temporary_folder(_any_file_name),
    ),
    "script_exec": (
        "scripts run by their #! line (and files passed by descriptor: pass_fds)",
        lambda: _in_a_temporary_folder(_script),
    ),
    "posix_clocks": (
        "POSIX clocks and timers (time.clock_gettime, signal.setitimer, signal.alarm)",
        lambda: hasattr(time, "clock_gettime") and hasattr(signal, "setitimer") and hasattr(signal, "alarm"),
    ),
    "select_on_pipes": ("select() on pipes (Windows' takes only sockets)", _select_on_pipes),
    "sleep_command": ("`sleep` command", lambda: shutil.which("sleep") is not None),
    "affinity": (
        "os.sched_setaffinity on two cores or more (a process chooses its cores)",
        lambda: hasattr(os, "sched_setaffinity") and len(os.sched_getaffinity(0)) >= 2,
    ),
    "posix_shell": (
        "POSIX shell as subprocess's shell (the docs' commands: quotes, # comments, pipes)",
        _posix_shell,
    ),
}


@functools.cache
def here(name: str) -> bool:
    """Whether this system has the feature `name` (a key of FEATURES)."""
    return FEATURES[name][1]()


def missing(*names: str) -> list[str]:
    """What of `names` (FEATURES' keys) this system lacks, each as a skip names it."""
    unknown = set(names) - set(FEATURES)
    if unknown:
        raise ValueError(f"needs_linux: no such feature {sorted(unknown)}: one of {sorted(FEATURES)}")
    return [FEATURES[name][0] for name in names if not here(name)]


def skip_reason(*names: str) -> str | None:
    """Why a test that needs `names` is skipped here, or None when this system has them all."""
    lacking = missing(*names)
    return f"needs Linux's {'; '.join(lacking)}: not on this system" if lacking else None
