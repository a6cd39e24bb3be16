"""A failed run says where in one line an editor can read: `prog.py:12: error: ZeroDivisionError: ...`.

The lines are read here as VS Code reads them: the problem matcher `ev3sim2d init vscode` writes into
tasks.json is applied to every line of the run's output, and what it captures (file, line, severity,
message) must be the program's place, with the file as the student gave it.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from ev3sim2d.commands import init


def _matcher() -> tuple[re.Pattern, dict]:
    """The problem matcher of the task `init vscode` writes: its regexp and its groups."""
    task = next(t for t in init.vscode_tasks() if t["label"] == init.RUN_TASK)
    pattern = task["problemMatcher"]["pattern"]
    return re.compile(pattern["regexp"]), pattern


def problems(output: str) -> list[dict]:
    """What VS Code's Problems panel would list: the matcher applied to each line of the output."""
    regexp, groups = _matcher()
    found = []
    for line in output.splitlines():
        match = regexp.match(line)
        if match:
            found.append({key: match.group(groups[key]) for key in ("file", "line", "severity", "message")})
    return found


def _run(folder: Path, program: str, *options) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", program, "--time", "2", "--hang-after", "1", *options],
        capture_output=True, text=True, cwd=folder, timeout=120,
    )  # fmt: skip


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "my robot").mkdir()
    return tmp_path


def test_a_failing_program_gives_one_problem_at_its_line_named_as_given(folder):
    (folder / "my robot" / "prog.py").write_text("import time\ntime.sleep(0.5)\nx = 1 / 0\n")
    done = _run(folder, "my robot/prog.py")
    assert done.returncode == 1
    assert problems(done.stdout + done.stderr) == [
        {
            "file": "my robot/prog.py",
            "line": "3",
            "severity": "error",
            "message": "ZeroDivisionError: division by zero",
        }
    ]
    assert 'File "my robot/prog.py", line 3' in done.stderr  # the traceback is still there, before it


def test_an_error_in_a_module_beside_the_program_is_at_the_programs_line_that_called_it(folder):
    """The place is the program's line that led to the error (as the run's last line says it); the
    traceback above it goes on into the module."""
    (folder / "my robot" / "helper.py").write_text("def drive():\n    return {}['speed']\n")
    (folder / "my robot" / "prog.py").write_text("import helper\nhelper.drive()\n")
    done = _run(folder, "my robot/prog.py")
    assert problems(done.stderr) == [
        {"file": "my robot/prog.py", "line": "2", "severity": "error", "message": "KeyError: 'speed'"}
    ]
    assert 'File "my robot/helper.py", line 2, in drive' in done.stderr


def test_a_syntax_error_is_a_problem_at_its_line(folder):
    (folder / "my robot" / "prog.py").write_text("speed = 50\nif speed > 10\n    print(speed)\n")
    done = _run(folder, "my robot/prog.py")
    assert done.returncode == 1
    assert problems(done.stderr) == [
        {"file": "my robot/prog.py", "line": "2", "severity": "error", "message": "SyntaxError: expected ':'"}
    ]


def test_a_stuck_program_is_a_problem_at_each_threads_line(folder):
    (folder / "my robot" / "prog.py").write_text(
        "import _thread, threading, time\n"
        "def blink():\n"
        "    while True:\n"
        "        time.sleep(0.1)\n"
        "threading.Thread(target=blink, name='blinker', daemon=True).start()\n"
        "lock = _thread.allocate_lock()\n"
        "lock.acquire()\n"
        "lock.acquire()\n"
    )
    done = _run(folder, "my robot/prog.py")
    assert done.returncode == 3, done.stderr  # hung
    assert problems(done.stderr) == [
        {"file": "my robot/prog.py", "line": "8", "severity": "error",
         "message": "stuck here, so the run was stopped (thread MainThread)"},
        {"file": "my robot/prog.py", "line": "4", "severity": "error",
         "message": "stuck here, so the run was stopped (thread blinker)"},
    ]  # fmt: skip


def test_a_program_still_running_at_the_time_limit_is_told_where_as_information(folder):
    (folder / "my robot" / "prog.py").write_text("x = 0\nwhile True:\n    x += 1\n")
    done = _run(folder, "my robot/prog.py")
    assert done.returncode == 0
    [found] = problems(done.stderr)
    assert (found["file"], found["severity"]) == ("my robot/prog.py", "info") and found["line"] in ("2", "3")
    assert found["message"] == "still running here at the time limit (thread MainThread)"


def test_a_program_that_finishes_gives_no_problem(folder):
    (folder / "my robot" / "prog.py").write_text("print('hello')\n")
    done = _run(folder, "my robot/prog.py")
    assert done.returncode == 0 and problems(done.stdout + done.stderr) == []


def test_what_a_program_prints_is_never_taken_for_a_problem(folder):
    """A program's own printed lines are shown after their time stamp: one that prints a line shaped
    like a problem does not put it in the Problems panel."""
    (folder / "my robot" / "prog.py").write_text("print('prog.py:1: error: all tests failed')\n")
    done = _run(folder, "my robot/prog.py")
    assert problems(done.stdout + done.stderr) == []


def test_the_file_a_program_names_itself_is_shown_escaped_on_one_line(folder):
    name = "evil\x1b[2J\nprog.py"
    program = folder / "my robot" / "x.py"
    program.write_text(f"exec(compile('1/0', {name!r}, 'exec'))\n")
    for line in _run(folder, "my robot/x.py").stderr.splitlines():
        assert "\x1b" not in line
    found = problems(_run(folder, "my robot/x.py").stderr)
    assert all("\n" not in p["file"] for p in found)


def test_the_pattern_reads_windows_paths_as_vs_code_would():
    regexp, groups = _matcher()
    match = regexp.match(r"C:\Users\Ana\robot\prog.py:12: error: ZeroDivisionError: division by zero")
    assert match and (match.group(groups["file"]), match.group(groups["line"])) == (
        r"C:\Users\Ana\robot\prog.py",
        "12",
    )
    assert regexp.match('  File "prog.py", line 3, in <module>') is None
    assert json.loads(json.dumps(groups))  # (the matcher is plain JSON)
