"""The student's program inside the brick: compiled as `__main__`, run as the brick's main task.

The file is read as Python reads it, whichever system wrote it: bytes, in UTF-8
or the encoding its BOM or coding line (PEP 263) names, with any line endings;
bytes Python would refuse are a SyntaxError with the line and the fix (the same
check as the simulator's, simulator/program.py: the two houses share no code).
How it ended goes back to the simulator in the `end` message: the status, and
for an exception the traceback cut to the program's and the shim's frames (the
brick's own frames are left out), with the line and the virtual time.
"""

from __future__ import annotations

import builtins
import codecs
import os
import re
import traceback

from . import suggestions
from .scheduler import RunOver

BRICK_DIR = os.path.dirname(os.path.realpath(__file__))  # (pathlib would cost each brick 8 ms)
MAX_TRACEBACK = 20_000


class Program:
    """A program file compiled as `__main__` (its source as bytes, as read from the file, or as text)."""

    def __init__(self, path: str, source: bytes | str) -> None:
        self.path = path
        if isinstance(source, bytes):
            source_text(source, path)  # SyntaxError for bytes Python would refuse
        self.code = compile(source, path, "exec", dont_inherit=True)  # honours the BOM and coding line

    @classmethod
    def read(cls, path: str) -> Program:
        """The program in the file at `path` (OSError, SyntaxError, ValueError: it cannot be run)."""
        with open(path, "rb") as f:
            return cls(path, f.read())

    def run(self) -> None:
        module = {"__name__": "__main__", "__file__": self.path, "__builtins__": builtins}
        exec(self.code, module)


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


def error_report(exc: BaseException, program_path: str, t_s: float) -> dict:
    """The program's exception as the simulator reports it (file, line, time, traceback)."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if not f.filename.startswith(BRICK_DIR)]
    text = "Traceback (most recent call last):\n" + "".join(traceback.format_list(frames))
    *first, last = traceback.format_exception_only(type(exc), exc)
    text += "".join(first) + suggestions.with_suggestion(last, exc)  # Python's "Did you mean", on any Python
    own = [f for f in frames if f.filename == program_path]
    where = own[-1] if own else (frames[-1] if frames else None)
    file, line = (program_path if own else where.filename, where.lineno) if where else (None, None)
    message = suggestions.with_suggestion(str(exc), exc).rstrip("\n")
    if not frames and isinstance(exc, SyntaxError) and exc.lineno:  # the program itself did not compile
        file, line, message = exc.filename, exc.lineno, exc.msg  # shown as Python shows it: no traceback
        text = "".join(traceback.format_exception_only(type(exc), exc))
    return {
        "type": type(exc).__name__,
        "message": message[:2000],
        "file": file,
        "line": line,
        "t_s": t_s,
        "traceback": text[-MAX_TRACEBACK:],
    }


MAX_THREADS_SAID = 64  # threads whose place an end message says, at most


def ending(tasks: list, program_path: str, scheduler) -> dict:
    """The end message's content: how the run ended, from the brick's side; for a run that did not end by
    itself (stopped by the simulator, a deadlock), `threads`: where each of the program's threads was,
    [thread name, file, line] (scheduler.positions)."""
    t = scheduler.now_s
    error = None
    for task in tasks:
        exc = task.error
        if exc is None or isinstance(exc, RunOver):
            continue
        if isinstance(exc, SystemExit) and exc.code in (None, 0):
            continue
        error = error_report(exc, program_path, t)
        break
    if error is not None:
        status = "error"
    elif scheduler.end_reason == "deadlock":
        status = "deadlock"
    elif scheduler.end_reason == "time_limit":
        status = "time_limit"
    elif scheduler.end_reason == "stopped":
        status = "stopped"
    else:
        status = "finished"
    how = {"t_us": scheduler.now_us, "status": status, "error": error}
    if scheduler.where and status in ("deadlock", "time_limit", "stopped"):
        how["threads"] = scheduler.where[:MAX_THREADS_SAID]
    return how
