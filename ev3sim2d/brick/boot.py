"""The brick process's start: connect, load the trusted parts, enter the sandbox, run the program, report.

The simulator starts it as `python -s -S -B -P boot.py FD MEMORY_FD ROOT` with a
short fixed environment: FD is the connection (one end of a socket pair),
MEMORY_FD the shared memory of a SharedChannel (-1: the messages go through the
socket), ROOT the folder that holds the `ev3sim2d` package.  Where a socket cannot
be handed to a new process (Windows), it starts it as `boot.py tcp PORT ROOT` with
a one-time token on its standard input, and the brick connects to the simulator
over loopback TCP (protocol/loopback.py).  Only the standard library, ev3sim2d.brick,
ev3sim2d.protocol and the ev3dev2 shim are loaded here: nothing of the world,
the devices, the lesson or the grader exists in this process.

`boot.py zygote CONTROL_FD ROOT SHIM_ROOT SITE_PACKAGES` starts a zygote instead
(zygote.py): it loads the same and forks a brick per request, which goes on
from run_brick as a fresh brick goes on from main.

Order matters: the welcome (configuration) arrives first; the virtual clock
and the shim are installed while every file may still be read; then the
sandbox closes the process in (sandbox.py); only then is the program's file
read and run.  The `end` message says how it ended.
"""

from __future__ import annotations

import os
import sys


def _connect(fd: int, memory_fd: int):
    import socket

    from ev3sim2d.protocol import Channel, SharedChannel

    sock = socket.socket(fileno=fd)
    if memory_fd >= 0:
        return SharedChannel(sock, memory_fd, simulator=False)
    return Channel(sock)


def _connect_tcp(port: int):
    from ev3sim2d.protocol.loopback import connect

    token = sys.stdin.readline().strip()
    sys.stdin.close()
    return connect(port, token)


def main(argv: list[str]) -> int:
    if sys.path and os.path.dirname(os.path.abspath(__file__)) == os.path.abspath(sys.path[0] or "."):
        del sys.path[0]  # (a Python without -P put this folder first: the program must not import from it)
    if argv[1] == "zygote":
        return _zygote(int(argv[2]), argv[3], argv[4], json_list(argv[5]))
    root = argv[3]
    sys.path.insert(0, root)
    if argv[1] == "tcp":
        return run_brick(lambda: _connect_tcp(int(argv[2])), root)
    fd, memory_fd = int(argv[1]), int(argv[2])
    return run_brick(lambda: _connect(fd, memory_fd), root, fd)


def json_list(text: str) -> list[str]:
    import json

    return [str(p) for p in json.loads(text)]


def _zygote(control_fd: int, root: str, shim_root: str, site_packages: list[str]) -> int:
    """Load everything a brick loads before its program, then fork a brick per request (zygote.py)."""
    import gc
    import importlib

    sys.path[:0] = [root, shim_root]
    sys.path.extend(p for p in site_packages if p not in sys.path)
    import ev3sim2d.protocol  # noqa: F401
    from ev3sim2d.brick import sandbox, zygote  # noqa: F401
    from ev3sim2d.brick.run import SHIM_MODULES

    for name in SHIM_MODULES:
        importlib.import_module(name)
    gc.collect()
    gc.freeze()  # a forked brick's collections never walk (and so never copy) the zygote's pages
    return zygote.serve(
        control_fd, root, lambda fd, memory, top: run_brick(lambda: _connect(fd, memory), top, fd)
    )


def run_brick(connect, root: str, fd: int | None = None) -> int:
    """A brick's life from its connection on: welcome, runtime and shim, sandbox, hello, program."""
    from ev3sim2d.brick import sandbox  # noqa: F401 - before the runtime makes threads and sleep virtual
    from ev3sim2d.protocol import PROTOCOL, ProtocolError

    channel = connect()
    fd = channel.fileno() if fd is None else fd
    try:
        welcome = channel.receive(timeout_s=120)
    except ProtocolError as err:
        print(f"the brick could not read its welcome: {err}", file=sys.stderr)
        return 2
    if not welcome or welcome[0] != "welcome" or welcome[1].get("protocol") != PROTOCOL:
        channel.send(["end", {"t_us": 0, "status": "refused", "error": None}])
        return 2
    config = welcome[1]
    if config["shim_root"] not in sys.path:
        sys.path[1:1] = [config["shim_root"]]
    sys.path.extend(p for p in config.get("site_packages", ()) if p not in sys.path)

    from ev3sim2d.brick.run import BrickRun

    brick = BrickRun(channel, config)
    brick.prepare()  # the virtual clock, the shim: before the sandbox, while the files are readable
    report = _enter_sandbox(config, fd)
    sys.path.remove(root)  # the program finds only the shim, Python's own and third-party packages
    sys.path.extend(p for p in config.get("site_packages", ()) if p not in sys.path)  # (a wheel's root)
    channel.send(["hello", {"protocol": PROTOCOL, "sandbox": report, "python": sys.version.split()[0]}])
    brick.run()
    return 0


def _enter_sandbox(config: dict, fd: int) -> dict:
    policy = config.get("sandbox")
    if policy is None:
        return {"sandbox": "off: the simulator asked for none"}
    try:
        from ev3sim2d.brick import sandbox
    except ImportError as err:  # pragma: no cover - an incomplete installation
        return {"sandbox": f"off: {err}"}
    read_paths = [*policy["read_paths"], *sandbox.default_read_paths()]
    return sandbox.enter(
        sandbox.SandboxPolicy(
            read_paths=read_paths,
            write_paths=policy["write_paths"],
            keep_fds=[fd],
            cpu_s=policy["cpu_s"],
            memory_mb=policy["memory_mb"],
            file_mb=policy["file_mb"],
            processes=policy["processes"],
        )
    )


if __name__ == "__main__":
    code = main(sys.argv)
    sys.stdout.flush()
    os._exit(code)
