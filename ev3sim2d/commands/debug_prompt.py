"""The debugger's prompt in the terminal: `breakpoint()` in a program, or `ev3sim2d run --debug`.

A program stopped in its brick's debugger (brick/debugger.py) asks this front end what to do; while the
student reads and types, the whole world waits in virtual time.  The prompt is pdb's, in short:

    s(tep)  n(ext)  r(eturn)  c(ontinue)  w(here)  p EXPRESSION  b [FILE:]LINE  b  cl(ear)  q(uit)  h(elp)

`q` ends the run as Ctrl+C does.  At the end of its input (a closed terminal, an editor that gives it
none) the program goes on.  What the program chose (its file names, its source lines, its values) is
shown escaped.
"""

from __future__ import annotations

import os
import sys

from ..grading.safe_text import one_line
from ..simulator.run import shown_file

HELP = """\
(an empty line)   the last command again
s(tep)            run the current line, stopping in the first function it calls
n(ext)            run the current line, stopping at the next one here
r(eturn)          run on until the current function returns
c(ontinue)        run on until a breakpoint (or breakpoint() in the program)
w(here)           the program's calls that led here, the current one last
p EXPRESSION      the expression's value here (motor.position reads the robot now, at no cost)
b [FILE:]LINE     stop at that line of the program (or of a file beside it)
b                 the breakpoints
cl(ear)           remove every breakpoint
q(uit)            end the run, as Ctrl+C does
While the program is stopped, the world waits: no time passes, and writing to the robot is refused."""

RESUME = {"s": "step", "step": "step", "n": "next", "next": "next", "r": "return", "return": "return"}
RESUME |= {"c": "continue", "cont": "continue", "continue": "continue"}


class DebugPrompt:
    """The front end: __call__(robot index, shown, real, event) -> the command for the brick."""

    def __init__(self, robots: list[str] | None = None, stdin=None, stdout=None) -> None:
        self.robots = robots or []
        self.stdin = stdin or sys.stdin
        self.stdout = stdout or sys.stdout
        self.breakpoints: list[dict] = []
        self.last = ""  # the last command typed

    def __call__(self, index: int, shown: str, real: str, event: dict) -> dict:
        self._show(index, shown, real, event)
        while True:
            self.stdout.write("(ev3sim2d) ")
            self.stdout.flush()
            line = self.stdin.readline()
            if not line:  # the end of the input: the program goes on
                self.stdout.write("\n")
                return {"cmd": "continue"}
            typed = line.strip() or self.last  # (an empty line repeats the last command, as in pdb)
            self.last = typed
            command = self._command(typed, shown, real)
            if command is not None:
                return command

    def _command(self, line: str, shown: str, real: str) -> dict | None:
        """The command for the brick; None when the prompt answered by itself (help, a mistake)."""
        word, _, rest = line.partition(" ")
        rest = rest.strip()
        if word in RESUME:
            return {"cmd": RESUME[word]}
        if word in ("w", "where", "bt"):
            return {"cmd": "where"}
        if word in ("p", "pp", "print") and rest:
            return {"cmd": "eval", "expr": rest}
        if word in ("b", "break"):
            if not rest:
                self._say(self._breakpoint_list() or "no breakpoints")
                return None
            file, _, number = rest.rpartition(":")
            if not number.strip().isdigit():
                self._say("a breakpoint is b LINE, or b FILE:LINE")
                return None
            command = {"cmd": "break", "line": int(number)}
            if file:
                command["file"] = brick_file(file, shown, real)
            return command
        if word in ("cl", "clear"):
            return {"cmd": "clear"}
        if word in ("q", "quit", "exit"):
            raise KeyboardInterrupt
        if word in ("h", "help", "?"):
            self._say(HELP)
            return None
        self._say(f"{one_line(word)}: not a command; h for help")
        return None

    def _show(self, index: int, shown: str, real: str, event: dict) -> None:
        kind = event.get("event")
        robot = f", robot {self.robots[index]}" if len(self.robots) > 1 else ""
        if kind == "stopped":
            place = f"{one_line(shown_file(event['file'], shown, real))}:{event['line']}"
            self._say(
                f"ev3sim2d: stopped at {place} in {one_line(event['function'])} (thread "
                f"{one_line(event['thread'])}{robot}, at {event['t_us'] / 1e6:.3f} s of the run)\n"
                f"-> {one_line(event['source'])}"
            )
        elif kind == "stack":
            for frame in event.get("frames", []):
                place = f"{one_line(shown_file(frame['file'], shown, real))}:{frame['line']}"
                self._say(f"  {place} in {one_line(frame['function'])}\n    {one_line(frame['source'])}")
        elif kind == "value":
            self._say(one_line(event.get("text", "")))
        elif kind == "breakpoints":
            self.breakpoints = [
                {"file": shown_file(b["file"], shown, real), "line": b["line"]}
                for b in event.get("breakpoints", [])
            ]
            self._say(self._breakpoint_list() or "no breakpoints")
        else:
            self._say(f"ev3sim2d: {one_line(event.get('message', 'the debugger could not do that'))}")

    def _breakpoint_list(self) -> str:
        return "\n".join(f"breakpoint at {one_line(b['file'])}:{b['line']}" for b in self.breakpoints)

    def _say(self, text: str) -> None:
        self.stdout.write(text + "\n")
        self.stdout.flush()


def brick_file(file: str, shown: str, real: str) -> str:
    """A file the student names as the brick knows it: the program as they named it, a file by its path
    (an editor's absolute one too) in the program's folder, or by its name there, becomes the copy's."""
    real_dir = os.path.dirname(real)
    for named, folder in (
        (file, os.path.dirname(shown)),
        (os.path.abspath(file), os.path.dirname(os.path.abspath(shown))),
    ):
        if os.path.normcase(named) == os.path.normcase(os.path.join(folder, os.path.basename(shown))):
            return real
        if folder and os.path.normcase(named).startswith(os.path.normcase(os.path.join(folder, ""))):
            return os.path.join(real_dir, named[len(folder) + 1 :])
    return file if os.path.isabs(file) else os.path.join(real_dir, file)
