"""A program file as the simulator sees it before a run: there, readable, and valid Python.

The simulator never runs a program: a brick process does (ev3sim2d/brick/).
It reads and compiles the file first only to report a missing file, a file
Python cannot read as text, or a syntax error at once, with the line, before
any process is started.  A file is read as Python reads it, whichever system
wrote it: bytes, in UTF-8 or the encoding its BOM or coding line (PEP 263)
names, with any line endings.  The brick reads it the same way
(brick/program.py; the two houses share no code).
"""

from __future__ import annotations

import codecs
import re
import traceback
from pathlib import Path


class ProgramError(Exception):
    """A program that cannot be started (missing file, not text, syntax error)."""


class Program:
    """A program file, read and compiled (not run); `source` is its text as Python reads it."""

    def __init__(self, path: str | Path) -> None:
        self.path = Path(path)
        shown = str(self.path)  # as the user gave it (relative stays relative), as the run shows it
        try:
            data = self.path.read_bytes()
        except FileNotFoundError:
            raise ProgramError(f"{path}: no such program file") from None
        except IsADirectoryError:
            raise ProgramError(f"{path}: this is a folder; give the path of a .py file") from None
        except OSError as exc:
            raise ProgramError(f"{path}: cannot read the program ({exc.strerror})") from None
        try:
            self.source = source_text(data, shown)
            compile(data, shown, "exec", dont_inherit=True)  # honours the BOM and the coding line
        except SyntaxError as exc:
            where = f"{exc.filename}, line {exc.lineno}" if exc.lineno else shown
            caret = source_with_caret(exc)
            raise ProgramError(f"{where}: {exc.msg}" + (f"\n{caret}" if caret else "")) from None
        except ValueError as exc:  # source with a null byte
            raise ProgramError(f"{path}: {exc}") from None


# The coding line of PEP 263, as Python's tokenizer finds it: on line 1, or on line 2 below a comment.
_CODING = re.compile(rb"^[ \t\f]*#.*?coding[:=][ \t]*([-\w.]+)")
_BLANK = re.compile(rb"^[ \t\f]*(?:[#\r\n]|$)")
_LINE_END = re.compile(r"\r\n|\r|\n")


def source_text(data: bytes, filename: str) -> str:
    """A Python file's text, decoded as Python decodes it; SyntaxError (with the line and the fix) for
    bytes Python would refuse, e.g. a file saved as Windows-1252 without a coding line."""
    bom = data.startswith(codecs.BOM_UTF8)
    body = data[len(codecs.BOM_UTF8) :] if bom else data
    encoding, coding_line = "utf-8", None
    for number, line in enumerate(body.splitlines()[:2], start=1):
        found = _CODING.match(line)
        if found:
            encoding, coding_line = found.group(1).decode("ascii"), number
            break
        if not _BLANK.match(line):
            break
    try:
        codec = codecs.lookup(encoding).name
    except LookupError:
        raise SyntaxError(
            f"unknown encoding '{encoding}' in the coding line; write e.g. `# -*- coding: cp1252 -*-`, "
            "or save the file as UTF-8 and remove the line",
            (filename, coding_line, None, None),
        ) from None
    if bom and not codec.startswith("utf-8"):
        raise SyntaxError(
            f"the file starts with a UTF-8 mark (BOM) but its coding line says {encoding}; save the file "
            f"as UTF-8 and remove the coding line",
            (filename, coding_line, None, None),
        )
    try:
        text = body.decode(codec)
    except UnicodeDecodeError as err:
        raise _not_text(body, err, filename, encoding, coding_line) from None
    if "\0" in text:  # Python reads no further
        before = _LINE_END.split(text[: text.index("\0")])
        raise SyntaxError(
            "a null byte: this is not a Python text file (or it is saved as UTF-16); save the file as UTF-8",
            (filename, len(before), len(before[-1]) + 1, None),
        )
    return text


def _not_text(
    body: bytes, err: UnicodeDecodeError, filename: str, encoding: str, coding_line: int | None
) -> SyntaxError:
    """The first byte Python cannot read, at its line and column, and how to save the file so it can."""
    if body.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        message = "the file is saved as UTF-16 (Notepad calls it 'Unicode'); save the file as UTF-8"
        return SyntaxError(message, (filename, 1, None, None))
    if coding_line is None:
        message = (
            f"byte 0x{body[err.start]:02x} is not UTF-8 text (the file was saved in another encoding, e.g. "
            "Windows' cp1252); save the file as UTF-8, or add `# -*- coding: cp1252 -*-` as its first line"
        )
    else:
        message = (
            f"byte 0x{body[err.start]:02x} is not {encoding} text, as the coding line (line {coding_line}) "
            "says the file is; save the file as UTF-8 and remove the coding line, or name its real encoding"
        )
    before = _LINE_END.split(body[: err.start].decode(encoding, "replace"))
    text = before[-1] + _LINE_END.split(body[err.start :].decode(encoding, "replace"), maxsplit=1)[0]
    return SyntaxError(message, (filename, len(before), len(before[-1]) + 1, text))


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
