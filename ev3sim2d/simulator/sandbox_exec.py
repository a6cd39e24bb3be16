"""Confining a brick with sandbox-exec (macOS's Seatbelt), where the system has one.

On Linux a brick walls itself in (ev3sim2d/brick/sandbox.py: Landlock, seccomp, namespaces).
Where none of those exist but `/usr/bin/sandbox-exec` does (macOS 12-15: deprecated in its man
page, still shipped, and used by Bazel, Nix and many tools that confine a child), the simulator
starts the brick through it: `wrap(argv, [scratch])` gives `[sandbox-exec, "-p", PROFILE, *argv]`.
sandbox-exec applies the profile to itself and then execs the command, so the brick keeps the
pid Popen reports, its session and the fds passed to it; every process the program starts
inherits the profile, and a process cannot leave or loosen its profile.

The profile, in SBPL (Apple's Scheme dialect, where the last rule that matches an operation wins):

    (version 1)
    (allow default)        everything else stays as without this layer: the brick's other walls
                           (fixed environment, closed fds, limits, the simulator's checks) hold.
    (deny network*)        no connect, bind, listen or accept, for TCP, UDP and unix sockets alike:
                           no internet, no 127.0.0.1, no daemon's socket by path (mDNSResponder too,
                           so no DNS).
    (deny file-write*)     no writing anywhere: create, write, truncate, unlink, rename, mode, owner,
                           times, flags, extended attributes ...
    (allow file-write* (literal "/dev/null") (subpath SCRATCH) ...)
                           ... except beneath the scratch folder (given by the caller), and
                           /dev/null, which programs and libraries open for writing
                           (subprocess.DEVNULL, output thrown away).
    (deny file-link)       no hard links, anywhere: `file-link` is an operation of its own, outside
                           `file-write*`, and a link made in the scratch folder to a file elsewhere
                           (the same volume: /var/folders and $HOME are) would be a second name,
                           beneath the scratch folder, of a file the program must not write.

Nothing else is writable, because a Python interpreter provably needs nothing else: `-B` and
PYTHONDONTWRITEBYTECODE write no bytecode; HOME and TMPDIR are the scratch folder (tempfile,
caches of numpy or matplotlib go there); the console (fds 1 and 2) is a file the simulator opened
in the scratch folder; the connection is an inherited socket pair.  Refused, on purpose:
/dev/tty (a brick has no terminal) and /dev/dtracehelper (dyld offers DTrace probes there; a
refusal is silent).

The connection to the simulator keeps working under `(deny network*)`.  Seatbelt sees sockets
only through the kernel's MAC hooks, and XNU calls them (bsd/kern/uipc_syscalls.c, sys_socket.c,
uipc_socket.c, xnu-11417) on connect, bind, listen and accept; on a send only when it names a
destination (sendto or sendmsg with an address); on a receive only for a socket that is neither
connected nor of a protocol that needs a connection, and on the sender's address only for an
unconnected socket; read() and write() on a socket call none.  A socket pair is connected from
birth, so sending and receiving on the inherited end never meet the network rules.

Paths: Seatbelt matches the path the kernel resolves, symlinks followed, so each write path goes
in as its real path (/tmp is /private/tmp, /var is /private/var and the system's temporary folder
lives in /var/folders).  Every mismatch (another spelling, a case difference) fails closed: the
allow rule does not match and the write is refused.  In an SBPL string literal (read by
TinyScheme's reader) only a backslash and a double quote are special; both are escaped with a
backslash and everything else stands for itself (spaces, parentheses, semicolons, newlines,
non-ASCII), so no folder name can end the string and add a rule.

`available()` checks the feature, not the platform: an executable sandbox-exec at its fixed
place (never looked up in PATH, which the caller's environment controls) that runs this
interpreter under the profile.  It cannot where the simulator itself runs in a sandbox
(sandbox_apply: Operation not permitted) or where the system refuses the profile; the layer is
then "off: <why>" in the brick's report (`describe()`) and the brick runs with its other walls,
as with every layer a system lacks.

What this layer leaves open (docs/grading-security.md): reading (every file the user can read,
hidden variants included, unless file permissions keep them out), Mach and XPC services (a
program may ask launchd, LaunchServices or another daemon to act for it outside the sandbox),
signals to other processes of the same user, and resource limits.
"""

from __future__ import annotations

import functools
import os
import subprocess
import sys

SANDBOX_EXEC = "/usr/bin/sandbox-exec"
PROBE_TIMEOUT_S = 30.0  # a first start of Python on macOS may wait for the system's malware scan
ALWAYS_WRITABLE = ("/dev/null",)  # literal paths, besides the write paths (see the module's docstring)


def available() -> str | None:
    """The path of sandbox-exec if a brick can be started through it here, else None."""
    return _probe()[0]


def describe() -> str:
    """This layer in the brick's isolation report: "on (...)", or "off: why"."""
    path, why_off = _probe()
    return "on (no network, writes only in the scratch folder)" if path else f"off: {why_off}"


def profile(write_paths: list[str]) -> str:
    """The SBPL profile: no network, no hard links, writes only beneath write_paths and /dev/null."""
    writable = [f"(literal {_string_literal(path)})" for path in ALWAYS_WRITABLE]
    for path in write_paths:
        rule = f"(subpath {_string_literal(_real_path(path))})"
        if rule not in writable:
            writable.append(rule)
    return "\n".join(
        [
            "(version 1)",
            "(allow default)",
            "(deny network*)",
            "(deny file-write*)",
            "(allow file-write*",
            *(f"    {rule}" for rule in writable),
            ")",
            "(deny file-link)",
            "",
        ]
    )


def wrap(argv: list[str], write_paths: list[str]) -> list[str]:
    """argv run under the profile through sandbox-exec; argv unchanged where that is unavailable."""
    path = available()
    if path is None:
        return list(argv)
    return [path, "-p", profile(write_paths), *argv]


def _real_path(path: str) -> str:
    if "\0" in path:
        raise ValueError(f"a write path cannot hold a NUL character: {path!r}")
    return os.path.realpath(path)


def _string_literal(text: str) -> str:
    """text as an SBPL string literal: a backslash and a double quote escaped, the rest kept."""
    if "\0" in text:
        raise ValueError(f"an SBPL string cannot hold a NUL character: {text!r}")
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


@functools.cache
def _probe() -> tuple[str | None, str]:
    """(path of sandbox-exec, "") if it runs this interpreter under a profile, else (None, why not);
    once per process."""
    if not os.access(SANDBOX_EXEC, os.X_OK):
        return None, f"no executable {SANDBOX_EXEC} on this system"
    command = [SANDBOX_EXEC, "-p", profile([]), sys.executable, "-S", "-c", ""]
    try:
        done = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, timeout=PROBE_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return None, f"{SANDBOX_EXEC} did not run Python within {PROBE_TIMEOUT_S:.0f} s"
    except OSError as err:
        return None, f"{SANDBOX_EXEC} cannot be run: {err.strerror}"
    if done.returncode != 0:
        said = done.stderr.decode("utf-8", "replace").strip().splitlines()
        return None, f"{SANDBOX_EXEC} refused the profile ({said[-1] if said else f'exit {done.returncode}'})"
    return SANDBOX_EXEC, ""
