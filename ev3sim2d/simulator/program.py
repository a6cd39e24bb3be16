"""A program file as the simulator sees it before a run: there, a file, and not too large.

The simulator never runs a program, and never parses or compiles one either: a student's source is
read and compiled only inside its brick, under the brick's limits (brick/program.py), where a syntax
error, a file Python cannot read as text, or a source too deep for the parser ends the run at 0 s with
what Python says (simulator/run.py: start_failure shows it with its line and caret).  Here the file is
only looked at: that it is there, a regular file, readable, and at most MAX_PROGRAM_BYTES (a program
for an EV3 is a few kilobytes; a larger one is refused before any process starts).
"""

from __future__ import annotations

import os
import stat
import traceback
from pathlib import Path

MAX_PROGRAM_BYTES = 1 * 2**20


class ProgramError(Exception):
    """A program that cannot be started (a missing file, a folder, a file over the size limit)."""


class Program:
    """A program file, looked at (not read, not compiled)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        try:
            info = os.stat(self.path)
        except FileNotFoundError:
            raise ProgramError(f"{path}: no such program file") from None
        except OSError as exc:
            raise ProgramError(f"{path}: cannot read the program ({exc.strerror})") from None
        if stat.S_ISDIR(info.st_mode):
            raise ProgramError(f"{path}: this is a folder; give the path of a .py file")
        if not stat.S_ISREG(info.st_mode):
            raise ProgramError(f"{path}: not a file (a device or a pipe?); give the path of a .py file")
        if info.st_size > MAX_PROGRAM_BYTES:
            raise ProgramError(
                f"{path}: {info.st_size} bytes, more than a program may have ({MAX_PROGRAM_BYTES} bytes); "
                "is this the right file?"
            )
        if not os.access(self.path, os.R_OK):
            raise ProgramError(f"{path}: cannot read the program (no permission)")


def source_with_caret(exc: SyntaxError) -> str:
    """The line of a syntax error and a caret (^) under where it is, as Python shows them."""
    shown = traceback.format_exception_only(SyntaxError, exc)[
        1:-1
    ]  # between "File ..., line N" and the message
    lines = [
        line.rstrip().replace("\ufeff", "") for part in shown for line in part.splitlines() if line.strip()
    ]
    if not lines and exc.text:
        lines = [f"    {exc.text.strip()}"]
    return "\n".join(lines)
