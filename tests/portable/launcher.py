"""A Python interpreter that is a Windows-like or macOS-like one (other_system.py), as `python` is.

Written by `launcher_for(kind, folder)` as an executable file whose first line runs this
interpreter: it applies other_system.apply(kind), makes itself sys.executable (so that every Python
process ev3sim2d starts is the same kind) and then does what `python [flags] -m module | -c code |
script ...` does.
"""

from __future__ import annotations

import os
import stat
import sys
from pathlib import Path

BODY = r"""
import os, runpy, sys
sys.path.insert(0, {here!r})
import other_system
other_system.apply({kind!r})
del sys.path[0]
sys.executable = os.path.abspath(sys.argv[0])
if sys.path and sys.path[0] == os.path.dirname(sys.executable):
    del sys.path[0]  # this launcher's folder: the program's own first entry takes its place below
args = sys.argv[1:]
flags = []
while args and args[0].startswith("-") and args[0] not in ("-m", "-c", "-"):
    flags += args[:2] if args[0] in ("-X", "-W") else args[:1]
    args = args[2:] if args[0] in ("-X", "-W") else args[1:]
if "-B" in flags:
    sys.dont_write_bytecode = True
if not args:
    raise SystemExit("launcher: no program")
safe_path = "-P" in flags or "-I" in flags
if args[0] == "-m":
    sys.argv = args[1:]
    if not safe_path:
        sys.path.insert(0, os.getcwd())  # as `python -m` puts the working folder first
    runpy.run_module(args[1], run_name="__main__", alter_sys=True)
elif args[0] == "-c":
    sys.argv = ["-c", *args[2:]]
    if not safe_path:
        sys.path.insert(0, "")  # as `python -c` does: the working folder
    exec(compile(args[1], "<string>", "exec"), {{"__name__": "__main__"}})
else:
    sys.argv = args
    if not safe_path:
        sys.path.insert(0, os.path.dirname(os.path.abspath(args[0])))
    runpy.run_path(args[0], run_name="__main__")
"""


def launcher_for(kind: str, folder: Path) -> Path:
    """An executable `python-KIND` in folder: a Python that looks like KIND ("windows", "macos")."""
    path = Path(folder) / f"python-{kind}"
    body = BODY.format(here=str(Path(__file__).resolve().parent), kind=kind)
    path.write_text(f"#!{sys.executable}\n{body}", encoding="utf-8")
    path.chmod(path.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return path


if __name__ == "__main__":  # python tests/portable/launcher.py KIND FOLDER: write one, print its path
    print(launcher_for(sys.argv[1], Path(sys.argv[2] if len(sys.argv) > 2 else os.getcwd())))
