"""The lines an editor reads from a run: `prog.py:12: error: ZeroDivisionError: division by zero`.

Besides the traceback, a run that failed says where in one line per place, as compilers do, so that an
editor's problem matcher (VS Code's tasks, PyCharm's output filters, Thonny's shell) can take the student
to the line: FILE:LINE: SEVERITY: TEXT, the file as the student named it.  `error` for the program's
error (or a source that does not compile) and for each thread of a program stopped as stuck (hung, or in
a deadlock); `info` for each thread of a program still running at the time limit, which is how many
robot programs end.  The pattern an editor needs is PATTERN; docs/editors.md shows it in each editor.

Everything here comes from the program (its file names, its error's text, its threads' names): it is
shown escaped, on one line, as the rest of what a program chose (grading/safe_text.py).
"""

from __future__ import annotations

from ..grading.safe_text import one_line
from ..simulator.run import RunResult

# file, line, severity, message: the regular expression a problem matcher is given.  A line the program
# printed starts with its time, `[   1.250 s] `: never a problem, whatever it says.
PATTERN = r"^([^\[\s].*?):(\d+): (error|warning|info): (.*)$"

STOPPED = {
    "hung": ("error", "stuck here, so the run was stopped"),
    "time_limit": ("info", "still running here at the time limit"),
}


def problem_lines(result: RunResult) -> list[str]:
    """One line per place an editor should show: the error's, or each stopped thread's."""
    lines = []
    error = result.error
    if error and error.get("file") and error.get("line"):
        message = (error.get("message") or "").strip().splitlines()
        text = f"{error['type']}: {message[0]}" if message else error["type"]
        lines.append(_line(error["file"], error["line"], "error", text))
    many = len(result.robots) > 1
    for robot in result.robots:
        if robot["status"] not in STOPPED:
            continue
        severity, what = STOPPED[robot["status"]]
        for place in robot.get("stopped_at", []):
            who = f"thread {place['thread']}" + (f", robot {robot['robot']}" if many else "")
            lines.append(_line(place["file"], place["line"], severity, f"{what} ({who})"))
    return lines


def _line(file: str, line: int, severity: str, text: str) -> str:
    return f"{one_line(file)}:{line}: {severity}: {one_line(text)}"
