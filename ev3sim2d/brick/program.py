"""The student's program inside the brick: compiled as `__main__`, run as the brick's main task.

How it ended goes back to the simulator in the `end` message: the status, and
for an exception the traceback cut to the program's and the shim's frames (the
brick's own frames are left out), with the line and the virtual time.
"""

from __future__ import annotations

import builtins
import os
import traceback

from .scheduler import RunOver

BRICK_DIR = os.path.dirname(os.path.realpath(__file__))  # (pathlib would cost each brick 8 ms)
MAX_TRACEBACK = 20_000


class Program:
    """A program file compiled as `__main__`."""

    def __init__(self, path: str, source: str) -> None:
        self.path = path
        self.code = compile(source, path, "exec", dont_inherit=True)

    def run(self) -> None:
        module = {"__name__": "__main__", "__file__": self.path, "__builtins__": builtins}
        exec(self.code, module)


def error_report(exc: BaseException, program_path: str, t_s: float) -> dict:
    """The program's exception as the simulator reports it (file, line, time, traceback)."""
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if not f.filename.startswith(BRICK_DIR)]
    text = "Traceback (most recent call last):\n" + "".join(traceback.format_list(frames))
    text += "".join(traceback.format_exception_only(type(exc), exc))
    own = [f for f in frames if f.filename == program_path]
    where = own[-1] if own else (frames[-1] if frames else None)
    return {
        "type": type(exc).__name__,
        "message": str(exc)[:2000],
        "file": program_path if own else (where.filename if where else None),
        "line": where.lineno if where else None,
        "t_s": t_s,
        "traceback": text[-MAX_TRACEBACK:],
    }


def ending(tasks: list, program_path: str, scheduler) -> dict:
    """The end message's content: how the run ended, from the brick's side."""
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
    return {"t_us": scheduler.now_us, "status": status, "error": error}
