"""A debugger inside the brick, on the standard library's bdb, that talks through the brick's link.

It needs no network and no process of its own: where the program stops (`breakpoint()`, a breakpoint
by line, a step), the brick asks the simulator what to do with an answered call, `debug` (brick/link.py,
docs/protocol.md), which carries an event and brings back a command; the simulator's front end (a
terminal prompt, or a Debug Adapter Protocol server) asks the student.  While it is stopped:

- the program's thread holds the brick's turn and passes no tick, so the world, and every other robot,
  waits, for as long as the student looks;
- its clock is frozen (scheduler.frozen): the stop costs no virtual time, a value read to look at it
  (`motor.position`) comes from the last snapshot at no cost, its lines cost nothing, and a write to a
  device, a sleep or a wait is refused: looking changes nothing;
- `random`'s state is kept, so a run stepped through gives the same trace as the same run without it.

Only the program's own files are stepped through (scheduler.program_file): the shim's, the brick's and
Python's are stepped over.  Events: `stopped` (why, thread, file, line, function, source line), then one
answer per command: `stack`, `value`, `variables`, `breakpoints`, `error`.  Commands: continue, step, next,
return, where, eval, variables, break, clear.
"""

from __future__ import annotations

import bdb
import builtins
import linecache
import os
import random
import sys
import threading
import types

from .cpu_time import CpuTime

TEXT = 2000  # characters of a value or a source line sent, at most
FRAMES = 64  # frames of a stack sent, at most
RESUMING = {"continue", "step", "next", "return"}
VARIABLES = 200  # names of a scope sent, at most
SKIPPED_KINDS = (types.ModuleType, types.FunctionType, types.BuiltinFunctionType, type)


class BrickDebugger(bdb.Bdb):
    """The program's debugger: `breakpoint()` stops in it, and `start` stops at the program's first line."""

    def __init__(self, link, scheduler, folder: str) -> None:
        super().__init__()
        self.link = link
        self.scheduler = scheduler
        self.folder = folder  # the program's folder: breakpoints given by a relative name are in it

    # ------------------------------------------------------------ starting
    def breakpoint(self, *args, **kwargs) -> None:
        """sys.breakpointhook: stop at the line after the call, in the caller's frame."""
        if self.scheduler.task_for_thread() is None:
            return  # (the brick's own threads are not the program's)
        threading.settrace(self.trace_dispatch)  # threads started from now on stop at breakpoints too
        self.set_trace(sys._getframe(1))

    def start(self) -> None:
        """In the program's main thread, before it runs: stop at its first line."""
        threading.settrace(self.trace_dispatch)
        self.reset()
        self.set_step()
        sys.settrace(self.trace_dispatch)

    # ---------------------------------------------------------- which frames
    def stop_here(self, frame) -> bool:
        return self.scheduler.program_file(frame.f_code.co_filename) and super().stop_here(frame)

    def user_line(self, frame) -> None:
        reason = "breakpoint" if self.break_here(frame) else "step"
        self._interact(frame, reason)

    # ------------------------------------------------------------ stopped
    def _interact(self, frame, reason: str) -> None:
        task = self.scheduler.task_for_thread()
        event = {
            "event": "stopped",
            "reason": reason,
            "thread": task.thread_name if task is not None else "MainThread",
            **self._place(frame),
            "t_us": self.scheduler.now_us,
            "threads": [t.thread_name for t in self.scheduler.tasks if not t.done][:FRAMES],
        }
        line_function = getattr(builtins, CpuTime.LINE, None)
        self.scheduler.frozen = True
        setattr(builtins, CpuTime.LINE, _free_line)  # (what is evaluated costs nothing)
        try:
            while True:
                command = self.link.call("debug", event)
                event = self._do(command if type(command) is dict else {}, frame)
                if event is None:
                    return
        finally:
            self.scheduler.frozen = False
            if line_function is not None:
                setattr(builtins, CpuTime.LINE, line_function)

    def _do(self, command: dict, frame) -> dict | None:
        """Carry out one command: None once the program goes on, else the event that answers it."""
        what = command.get("cmd")
        if what in RESUMING:
            if what == "continue":
                self.set_continue()
            elif what == "step":
                self.set_step()
            elif what == "next":
                self.set_next(frame)
            else:
                self.set_return(frame)
            return None
        if what == "where":
            return {"event": "stack", "frames": self._stack(self._frame_of(command.get("thread"), frame))}
        if what == "eval":
            return {"event": "value", **self._evaluate(str(command.get("expr", "")), frame)}
        if what == "variables":
            return {"event": "variables", "variables": self._variables(frame, command.get("scope"))}
        if what == "break":
            return self._break(command, frame)
        if what == "clear":
            self.clear_all_breaks()
            return {"event": "breakpoints", "breakpoints": []}
        return {"event": "error", "message": f"unknown command {str(what)[:50]!r}"}

    def _frame_of(self, thread, frame):
        """The innermost frame of the program's thread of that name (another thread than the one stopped
        waits where it is: at a sleep, a lock, a read), or the stopped one's."""
        current = self.scheduler.task_for_thread()
        for task in self.scheduler.tasks:
            if task.thread_name == thread and task is not current and not task.done:
                waiting = sys._current_frames().get(task.thread_id)
                return waiting if waiting is not None else frame
        return frame

    def _place(self, frame) -> dict:
        file, line = frame.f_code.co_filename, frame.f_lineno
        source = linecache.getline(file, line).strip()
        return {"file": file, "line": line, "function": frame.f_code.co_name, "source": source[:TEXT]}

    def _stack(self, frame) -> list[dict]:
        """The program's frames, outermost first (the brick's and the shim's left out)."""
        frames = []
        while frame is not None:
            if self.scheduler.program_file(frame.f_code.co_filename):
                frames.append(self._place(frame))
            frame = frame.f_back
        return frames[::-1][-FRAMES:]

    def _evaluate(self, expression: str, frame) -> dict:
        """The expression's value in the frame, as repr shows it; its error's, if it fails.  Looking
        changes nothing: random's state is kept, and the clock is frozen (writes, sleeps, waits refused)."""
        state = random.getstate()
        try:
            value = eval(expression, frame.f_globals, frame.f_locals)  # noqa: S307 - the student's own program
            return {"text": _short(_repr(value))}
        except Exception as err:  # noqa: BLE001 - the student's expression: its error is the answer
            return {"text": _short(f"{type(err).__name__}: {err}"), "error": True}
        finally:
            random.setstate(state)

    def _variables(self, frame, scope) -> list[dict]:
        """The frame's local (or, scope "globals", global) names and their values as repr shows them; the
        program's own, not modules, functions, classes nor dunders."""
        names = frame.f_globals if scope == "globals" else frame.f_locals
        shown = []
        for name, value in list(names.items()):
            if name.startswith("__") or isinstance(value, SKIPPED_KINDS):
                continue
            shown.append({"name": name, "value": _short(_repr(value)), "type": type(value).__name__})
            if len(shown) >= VARIABLES:
                break
        return shown

    def _break(self, command: dict, frame) -> dict:
        line = command.get("line")
        file = command.get("file") or frame.f_code.co_filename
        if type(line) is not int or type(file) is not str:
            return {"event": "error", "message": "a breakpoint is a line number, in a file of the program"}
        if not os.path.isabs(file):
            file = os.path.join(self.folder, file)
        if not self.scheduler.program_file(file):
            return {"event": "error", "message": f"{file} is not one of the program's files"}
        problem = self.set_break(self.canonic(file), line)
        if problem:
            return {"event": "error", "message": str(problem)[:TEXT]}
        breaks = [{"file": f, "line": n} for f, lines in self.get_all_breaks().items() for n in lines]
        return {"event": "breakpoints", "breakpoints": breaks}


def _repr(value) -> str:
    try:
        return repr(value)
    except Exception as err:  # noqa: BLE001 - a program's __repr__ may fail: that is what is shown
        return f"<{type(value).__name__}: repr failed: {type(err).__name__}>"


def _free_line() -> bool:
    return True


def _short(text: str) -> str:
    return text if len(text) <= TEXT else text[: TEXT - 1] + "…"
