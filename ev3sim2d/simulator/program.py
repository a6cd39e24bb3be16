"""A program file as the simulator sees it before a run: there, readable, and valid Python.

The simulator never runs a program: a brick process does (ev3sim2d/brick/).
It reads and compiles the file first only to report a missing file or a syntax
error at once, with the line, before any process is started.
"""

from __future__ import annotations

import traceback
from pathlib import Path


class ProgramError(Exception):
    """A program that cannot be started (missing file, syntax error)."""


class Program:
    """A program file, read and compiled (not run)."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        try:
            self.source = self.path.read_text(encoding="utf-8")
        except FileNotFoundError:
            raise ProgramError(f"{path}: no such program file") from None
        except (OSError, UnicodeDecodeError) as exc:
            raise ProgramError(f"{path}: cannot read the program ({exc})") from None
        try:
            compile(self.source, str(self.path), "exec", dont_inherit=True)
        except SyntaxError as exc:
            where = f"{exc.filename}, line {exc.lineno}" if exc.lineno else str(self.path)
            raise ProgramError(f"{where}: {exc.msg}\n{source_with_caret(exc)}") from None
        except ValueError as exc:  # source with a null byte
            raise ProgramError(f"{path}: {exc}") from None


def source_with_caret(exc: SyntaxError) -> str:
    """The line of a syntax error and a caret (^) under where it is, as Python shows them."""
    shown = traceback.format_exception_only(SyntaxError, exc)[
        1:-1
    ]  # between "File ..., line N" and the message
    lines = [line.rstrip() for part in shown for line in part.splitlines() if line.strip()]
    if not lines and exc.text:
        lines = [f"    {exc.text.strip()}"]
    return "\n".join(lines)
