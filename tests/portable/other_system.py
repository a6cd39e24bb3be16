"""Make this Linux CPython look like CPython on Windows or macOS, as far as what ev3sim2d uses goes.

A stand-in for the systems CI runs in its OS matrix, so that the portable code paths run here, in
every process: what the other system lacks is taken away (modules, functions, flags, signals, socket
families, subprocess options, the C library's Linux calls, /proc on macOS, dir_fd= on Windows), and a
few behaviours are imitated (Windows' socketpair over loopback TCP, its select() that takes only
sockets, its CDLL(None) that fails; macOS' RLIMIT_AS refusal, its infinite open-files limit, its
socketpair without SOCK_SEQPACKET, its fork that Python does not use by default).  It cannot give
Windows paths or consoles, hide /proc from the kernel (nor, on Windows, from Python), or make Linux
system call numbers other calls, and it keeps what the standard library's own POSIX code needs
(os.WNOHANG for subprocess): the real systems' runs belong to the workflow's OS matrix
(.github/workflows/tests.yml).

`python launcher.py -m ev3sim2d ...`: launcher.py applies this (EV3SIM2D_OTHER_SYSTEM says which)
and becomes sys.executable, so every Python process started through sys.executable (bricks,
grading workers, servers) is the same kind.
"""

from __future__ import annotations

import builtins
import errno
import os
import sys

BLOCKED_ON_WINDOWS = {
    "resource", "fcntl", "termios", "pwd", "grp", "tty", "pty", "crypt", "spwd", "nis", "syslog",
    "posix_ipc", "_posixshmem", "_posixsubprocess",
}  # fmt: skip
WINDOWS_LACKS_IN_OS = """fork forkpty setsid setpgid getpgid setpgrp getpgrp killpg getsid getuid geteuid
getgid getegid setuid setgid seteuid setegid getresuid getresgid setresuid setresgid getgroups setgroups
pidfd_open memfd_create sched_setaffinity sched_getaffinity sched_yield pipe2 unshare setns eventfd
wait3 wait4 waitid P_PID WEXITED WNOWAIT getloadavg mkfifo mknod chown lchown fchown sync
register_at_fork O_NOFOLLOW O_CLOEXEC O_DIRECTORY O_PATH O_NONBLOCK sysconf uname statvfs fchmod
getpriority setpriority nice posix_spawn posix_spawnp""".split()
MACOS_LACKS_IN_OS = """memfd_create pidfd_open sched_getaffinity sched_setaffinity getresuid getresgid
setresuid setresgid pipe2 unshare setns eventfd O_PATH O_DIRECT""".split()
WINDOWS_LACKS_IN_SIGNAL = """SIGKILL SIGSTOP SIGHUP SIGQUIT SIGALRM SIGCHLD SIGUSR1 SIGUSR2 SIGPIPE SIGCONT
SIGTSTP SIGTTIN SIGTTOU SIGXCPU SIGXFSZ SIGVTALRM SIGPROF SIGWINCH SIGIO SIGSYS SIGTRAP SIGBUS SIGPOLL
SIGPWR pthread_kill pthread_sigmask sigwait setitimer getitimer siginterrupt alarm pause
pidfd_send_signal ITIMER_REAL ITIMER_VIRTUAL ITIMER_PROF ItimerError SIG_BLOCK SIG_UNBLOCK
SIG_SETMASK""".split()
WINDOWS_LACKS_IN_TIME = """clock_gettime clock_gettime_ns clock_settime clock_getres CLOCK_BOOTTIME
CLOCK_MONOTONIC_RAW CLOCK_PROCESS_CPUTIME_ID CLOCK_THREAD_CPUTIME_ID CLOCK_TAI pthread_getcpuclockid
tzset""".split()
WINDOWS_LACKS_IN_SOCKET = """AF_UNIX SOCK_SEQPACKET SO_PEERCRED SCM_RIGHTS send_fds recv_fds sendmsg
recvmsg MSG_DONTWAIT sethostname if_nameindex""".split()
LINUX_ONLY_C_CALLS = {
    "prctl", "unshare", "capget", "capset", "setns", "mallopt", "pidfd_open", "process_vm_readv",
    "process_vm_writev",
}  # fmt: skip


def apply(kind: str) -> None:
    """Make this process a Windows-like ("windows") or macOS-like ("macos") Python."""
    if kind == "windows":
        _windows()
    elif kind == "macos":
        _macos()
    else:
        raise ValueError(f"unknown system {kind!r}: windows or macos")
    os.environ["EV3SIM2D_OTHER_SYSTEM"] = kind


def _remove(module, names) -> None:
    for name in names:
        if hasattr(module, name):
            delattr(module, name)


def _windows() -> None:
    # the packages with compiled parts have Windows builds of their own, and their Linux builds ask
    # Linux things at import (numpy: os.uname): load them first, their BLAS without threads of its own
    for name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
        os.environ.setdefault(name, "1")
    for name in ("numpy", "pymunk", "yaml", "PIL.Image", "cv2", "av"):
        try:
            __import__(name)
        except ImportError:
            pass
    import ctypes
    import ctypes.util
    import select
    import signal
    import socket
    import subprocess
    import time

    class NoPosixModules:
        def find_spec(self, name, path=None, target=None):
            if name in BLOCKED_ON_WINDOWS:
                raise ModuleNotFoundError(f"No module named {name!r}", name=name)
            return None

    sys.meta_path.insert(0, NoPosixModules())
    for name in BLOCKED_ON_WINDOWS:
        sys.modules.pop(name, None)
    _remove(os, WINDOWS_LACKS_IN_OS)
    os.supports_dir_fd.clear()  # no call takes dir_fd= there
    _remove(signal, WINDOWS_LACKS_IN_SIGNAL)
    _remove(time, WINDOWS_LACKS_IN_TIME)
    _remove(select, ("poll", "epoll", "POLLIN", "POLLOUT", "EPOLLIN"))
    _remove(socket, WINDOWS_LACKS_IN_SOCKET)

    def tcp_socketpair(family=socket.AF_INET, type=socket.SOCK_STREAM, proto=0):  # as Windows' is made
        with socket.create_server(("127.0.0.1", 0)) as listener:
            a = socket.create_connection(listener.getsockname())
            b, _ = listener.accept()
        return a, b

    socket.socketpair = tcp_socketpair
    real_select = select.select

    def sockets_only_select(r, w, x, *timeout):
        import stat

        for item in [*r, *w, *x]:
            fd = item if isinstance(item, int) else item.fileno()
            if not stat.S_ISSOCK(os.fstat(fd).st_mode):
                raise OSError(
                    10038, "[WinError 10038] An operation was attempted on something that is not a socket"
                )
        return real_select(r, w, x, *timeout)

    select.select = sockets_only_select
    real_init = subprocess.Popen.__init__

    def windows_popen(self, *args, **options):
        for name in ("pass_fds", "preexec_fn", "user", "group", "extra_groups", "umask"):
            if options.get(name) not in (None, (), [], -1):
                raise ValueError(f"{name} is not supported on Windows platforms")
        options.pop("start_new_session", None)  # (Windows ignores it)
        options.pop("process_group", None)
        return real_init(self, *args, **options)

    subprocess.Popen.__init__ = windows_popen
    subprocess.Popen.kill = lambda self: self.send_signal(9)  # TerminateProcess: no signal names
    subprocess.Popen.terminate = lambda self: self.send_signal(15)
    real_cdll = ctypes.CDLL.__init__

    def windows_cdll(self, name, *args, **options):
        if name is None:
            raise TypeError("argument of type 'NoneType' is not iterable")
        if isinstance(name, str) and (".so" in name or name.startswith("libc")):
            raise OSError(f"could not find module {name!r}")
        return real_cdll(self, name, *args, **options)

    ctypes.CDLL.__init__ = windows_cdll
    ctypes.util.find_library = lambda name: None


def _macos() -> None:
    import ctypes
    import platform
    import resource
    import socket

    _remove(os, MACOS_LACKS_IN_OS)
    real_socketpair = socket.socketpair

    def macos_socketpair(family=None, type=socket.SOCK_STREAM, proto=0):
        if type == socket.SOCK_SEQPACKET:
            raise OSError(errno.EPROTONOSUPPORT, "Protocol not supported")
        return real_socketpair(socket.AF_UNIX if family is None else family, type, proto)

    socket.socketpair = macos_socketpair
    real_getattr = ctypes.CDLL.__getattr__

    def macos_symbol(self, name):
        if name in LINUX_ONLY_C_CALLS:
            raise AttributeError(f"dlsym(RTLD_DEFAULT, {name}): symbol not found")
        if name == "syscall":
            raise AttributeError("the Linux system call numbers are other calls here: never made")
        return real_getattr(self, name)

    ctypes.CDLL.__getattr__ = macos_symbol
    infinite = 2**63 - 1  # macOS: the NOFILE hard limit is RLIM_INFINITY (until lowered), and that is this
    real_get, real_set = resource.getrlimit, resource.setrlimit
    resource.RLIM_INFINITY = infinite
    first_hard = real_get(resource.RLIMIT_NOFILE)[1]

    def getrlimit(which):
        soft, hard = real_get(which)
        if which == resource.RLIMIT_NOFILE and hard == first_hard:
            hard = infinite
        return (infinite if soft == -1 else soft, infinite if hard == -1 else hard)

    def setrlimit(which, limits):
        soft, hard = limits
        if which == resource.RLIMIT_AS and soft != infinite:  # macOS refuses it (cpython#78783)
            raise ValueError("current limit exceeds maximum limit")
        if which == resource.RLIMIT_NOFILE and hard == infinite:
            hard = first_hard
        real_set(which, (-1 if soft == infinite else soft, -1 if hard == infinite else hard))

    resource.getrlimit, resource.setrlimit = getrlimit, setrlimit

    def in_proc(path) -> bool:
        if not isinstance(path, str | bytes | os.PathLike):
            return False  # (a descriptor)
        name = os.fsdecode(os.fspath(path))
        return name == "/proc" or name.startswith("/proc/")

    def without_proc(real):
        """`real` (open, os.open, os.stat, ...), for which /proc does not exist: macOS has none."""

        asks = real is os.access  # (which answers False, where the others raise)

        def hidden(*args, **options):
            path = args[0] if args else options.get("path", options.get("file"))
            if in_proc(path) and options.get("dir_fd") is None:
                if asks:
                    return False
                raise FileNotFoundError(errno.ENOENT, "No such file or directory", path)
            return real(*args, **options)

        hidden.__name__, hidden.__qualname__, hidden.__doc__ = real.__name__, real.__qualname__, real.__doc__
        for able in (
            os.supports_dir_fd,
            os.supports_fd,
            os.supports_follow_symlinks,
            os.supports_effective_ids,
        ):
            if real in able:  # (what a program asks before it passes dir_fd=, a descriptor, ...)
                able.add(hidden)
        return hidden

    builtins.open = without_proc(builtins.open)
    for name in ("listdir", "scandir", "open", "stat", "lstat", "access"):
        setattr(os, name, without_proc(getattr(os, name)))
    import io

    io.open = builtins.open
    platform.machine = lambda: "arm64"
    import multiprocessing

    real_methods = multiprocessing.get_all_start_methods
    multiprocessing.get_all_start_methods = lambda: ["spawn", *(m for m in real_methods() if m != "spawn")]
