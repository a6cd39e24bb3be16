"""A program file as the simulator sees it before a run: there, readable, and valid Python.

The simulator never runs a program: a brick process does (ev3sim2d/brick/).
It reads and compiles the file first only to report a missing file or a syntax
error at once, with the line, before any process is started.
"""

from __future__ import annotations

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
            raise ProgramError(f"{where}: {exc.msg}\n    {(exc.text or '').rstrip()}") from None
        except ValueError as exc:  # source with a null byte
            raise ProgramError(f"{path}: {exc}") from None
