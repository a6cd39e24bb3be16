"""The machine a program finds itself on: an EV3 running ev3dev-stretch, whatever computer runs the brick.

What the last ev3dev-stretch release (R3, image ev3dev-stretch-ev3-generic-2020-04-10) says on an EV3:
- the host name (`socket.gethostname()`, `socket.getfqdn()`, `platform.node()`, `os.uname().nodename`):
  `ev3dev`, the image's /etc/hostname (ev3dev/docker-library, ev3dev-stretch/layers/base/brickstrap/
  _tar-only/etc/hostname);
- `os.uname()` (where Python has one: not on Windows), `platform.uname()` and so `system()`, `release()`,
  `version()`, `machine()`: `uname -a` on that image, `Linux ev3dev 4.14.117-ev3dev-2.3.5-ev3 #1 PREEMPT
  Sat Mar 7 12:54:39 CST 2020 armv5tejl` (https://github.com/ev3dev/ev3dev/issues/1411);
  `platform.processor()`: '' (Debian's `uname -p` says "unknown", which platform makes '');
- its CPU count (`os.cpu_count()`, `os.process_cpu_count()`, `os.sched_getaffinity()`): 1, the EV3's one
  ARM926EJ-S core (its /proc/cpuinfo lists `processor : 0` alone).  It also keeps a program's pools the
  same size on every computer.
So a program that checks `platform.machine()` takes its EV3 path, and one that prints its host name prints
the same on every computer.

The brick's own code keeps the real answers: each replacement answers as the real one outside the
program's threads, since the sandbox, entered after this is installed, picks its system call filter by
`platform.machine()` and reports `os.uname().release`.
"""

from __future__ import annotations

import os
import types
from collections.abc import Callable

HOSTNAME = "ev3dev"
UNAME = (
    "Linux",
    HOSTNAME,
    "4.14.117-ev3dev-2.3.5-ev3",
    "#1 PREEMPT Sat Mar 7 12:54:39 CST 2020",
    "armv5tejl",
)
CPUS = 1


class EV3Machine:
    """The replacements; `in_program()`: whether the calling thread is one of the program's."""

    def __init__(self, in_program: Callable[[], bool], patch: Callable[..., None]) -> None:
        self.in_program = in_program
        # (VirtualClocks.patch: a replacement of a built-in acts as one, and holds in a fresh copy of its module)
        self.patch = patch

    def install(self, after_import: Callable[[str, Callable], None]) -> None:
        self._os()
        after_import("_socket", self._socket)
        after_import("socket", self._socket)
        after_import("platform", self._platform)

    def _os(self) -> None:
        replaced: dict[str, Callable] = {}
        if hasattr(os, "uname"):  # (Windows' Python has none, nor a type for its result)
            real_uname, ev3 = os.uname, os.uname_result(UNAME)
            replaced["uname"] = lambda: ev3 if self.in_program() else real_uname()
        real_count = os.cpu_count
        replaced["cpu_count"] = lambda: CPUS if self.in_program() else real_count()
        real_process_count = getattr(os, "process_cpu_count", None)  # (Python 3.13)
        if real_process_count is not None:
            replaced["process_cpu_count"] = lambda: CPUS if self.in_program() else real_process_count()
        real_affinity = getattr(os, "sched_getaffinity", None)
        if real_affinity is not None:

            def sched_getaffinity(pid):
                found = real_affinity(pid)  # (the same errors for a process there is not)
                return set(range(CPUS)) if self.in_program() else found

            replaced["sched_getaffinity"] = sched_getaffinity
        self.patch(os, **replaced)

    def _socket(self, module: types.ModuleType) -> None:
        real_gethostname = module.gethostname

        def gethostname():
            return HOSTNAME if self.in_program() else real_gethostname()

        replaced: dict[str, Callable] = {"gethostname": gethostname}
        real_getfqdn = getattr(module, "getfqdn", None)  # (socket's, not _socket's)
        if real_getfqdn is not None:

            def getfqdn(name=""):
                if (
                    self.in_program()
                    and isinstance(name, str)
                    and name.strip() in ("", "0.0.0.0", "::", HOSTNAME)
                ):
                    return HOSTNAME  # (the EV3 finds no other name for itself: no DNS asked)
                return real_getfqdn(name)

            getfqdn.__doc__ = real_getfqdn.__doc__
            replaced["getfqdn"] = getfqdn
        self.patch(module, **replaced)

    def _platform(self, module: types.ModuleType) -> None:
        """platform.uname(), and so system(), node(), release(), version(), machine() and processor()."""
        real_uname = module.uname
        ev3 = module.uname_result(*UNAME)
        vars(ev3)["processor"] = ""  # (Python 3.9+ finds it when first asked, by running `uname -p`)

        def uname():
            return ev3 if self.in_program() else real_uname()

        uname.__doc__ = real_uname.__doc__
        self.patch(module, uname=uname)
