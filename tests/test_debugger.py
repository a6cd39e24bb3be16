"""A breakpoint freezes the whole world: the debugger inside the brick (brick/debugger.py) and its prompt
in the terminal (commands/debug_prompt.py), driven as a student drives them: `breakpoint()` in a program,
`ev3sim2d run --debug`, commands typed at `(ev3sim2d)`.

While the program is stopped no virtual time passes, a value read to look at it costs nothing and writes
nothing, `random` keeps its state, and a run stepped through gives the trace of the same run without the
debugger, fingerprint for fingerprint.
"""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ev3sim2d.simulator.brick_port import clean_debug_event

PROGRAM = """\
import random
from ev3dev2.motor import LargeMotor, OUTPUT_B, OUTPUT_C, MoveTank
tank = MoveTank(OUTPUT_B, OUTPUT_C)
left = LargeMotor(OUTPUT_B)
tank.on(30, 30)
speed = 10
breakpoint()
x = speed * 2
y = random.random()
tank.on_for_seconds(20, 40, 1.5)
print("x", x, "y", round(y, 6), left.position)
"""


def _run(folder: Path, *options, commands: str = "", program: str = "prog.py") -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", program, "--maze", "empty", "--time", "5", *options],
        input=commands, capture_output=True, text=True, cwd=folder, timeout=120,
    )  # fmt: skip


def _fingerprint(folder: Path, name: str) -> str:
    return json.loads((folder / name).read_text())["fingerprint"]


@pytest.fixture
def folder(tmp_path) -> Path:
    (tmp_path / "prog.py").write_text(PROGRAM)
    return tmp_path


def test_breakpoint_stops_the_program_and_looking_changes_nothing(folder):
    commands = "p speed\np left.position\np random.random()\np left.on(50)\nw\nn\np x\nc\n"
    done = _run(folder, "--summary", "debugged.json", commands=commands)
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert "ev3sim2d: stopped at prog.py:8 in <module> (thread MainThread, at 0.0" in out
    assert "-> x = speed * 2" in out
    assert "(ev3sim2d) 10\n" in out  # p speed
    assert (
        "(ev3sim2d) RuntimeError: the program is stopped in the debugger: writing to the robot is refused"
        in out
    )
    assert "  prog.py:8 in <module>\n    x = speed * 2" in out  # where
    assert "stopped at prog.py:9 in <module>" in out and "(ev3sim2d) 20\n" in out  # next, then p x
    looked = float(out.split("(ev3sim2d) ")[3].split("\n")[0])  # what p random.random() showed
    printed = out.split("] x 20 y ")[1].split()[0]
    assert round(looked, 6) == float(printed)  # the program's own draw is the one the look showed: state kept
    plain = _run(folder, "--summary", "plain.json")  # no input: breakpoint() goes on at once
    assert _fingerprint(folder, "debugged.json") == _fingerprint(folder, "plain.json")
    assert plain.stdout.split("] x")[1] == out.split("] x")[1]


def test_run_debug_stops_at_the_first_line_and_steps_to_a_breakpoint_with_the_same_run(folder):
    (folder / "nobreak.py").write_text(PROGRAM.replace("breakpoint()\n", "pass\n"))
    commands = "b 10\nc\ns\n\nn\nw\nc\n"  # (the empty line steps again, as in pdb)
    done = _run(folder, "--debug", "--summary", "stepped.json", commands=commands, program="nobreak.py")
    assert done.returncode == 0, done.stderr
    out = done.stdout
    assert out.startswith("ev3sim2d: stopped at nobreak.py:1 in <module> (thread MainThread, at 0.000 s")
    assert "breakpoint at nobreak.py:10" in out
    assert "stopped at nobreak.py:10" in out and "-> tank.on_for_seconds(20, 40, 1.5)" in out
    _run(folder, "--summary", "plain.json", program="nobreak.py")
    assert _fingerprint(folder, "stepped.json") == _fingerprint(folder, "plain.json")


def test_while_stopped_the_world_waits_however_long_the_student_looks(folder):
    """The robot drives at 30 % when breakpoint() is reached: read twice, a second of real time apart,
    its position is the same (no virtual time passed), and the run ends where a run without the stop
    does."""
    brick = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "run", "prog.py", "--maze", "empty", "--time", "5", "--summary", "s.json"],
        stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=folder,
    )  # fmt: skip
    try:
        readings = []
        for _ in range(2):
            brick.stdin.write("p left.position, left.speed\n")
            brick.stdin.flush()
            time.sleep(1.0)
        out, err = brick.communicate("c\n", timeout=120)
    finally:
        brick.kill()
    readings = [line for line in out.split("(ev3sim2d) ") if line.startswith("(")]
    assert len(readings) == 2 and readings[0] == readings[1], out
    _run(folder, "--summary", "plain.json")
    assert _fingerprint(folder, "s.json") == _fingerprint(folder, "plain.json")


def test_a_thread_stops_at_its_breakpoint_and_says_which_it_is(tmp_path):
    (tmp_path / "prog.py").write_text(
        "import threading, time\n"
        "def blink():\n"
        "    for i in range(3):\n"
        "        if i == 1:\n"
        "            breakpoint()\n"
        "        time.sleep(0.1)\n"
        "t = threading.Thread(target=blink, name='blinker')\n"
        "t.start()\n"
        "t.join()\n"
    )
    done = _run(tmp_path, commands="p i\nc\n")
    assert "stopped at prog.py:6 in blink (thread blinker, at 0.100 s of the run)" in done.stdout
    assert "(ev3sim2d) 1\n" in done.stdout


def test_quit_ends_the_run_as_ctrl_c_does(folder):
    done = _run(folder, commands="q\n")
    assert "interrupted" in done.stderr.strip().splitlines()[-1]


def test_grading_takes_no_breakpoint_and_refuses_debug(tmp_path):
    from tests.grading.lesson_maker import GOOD, write_lesson, write_program

    lesson = write_lesson(tmp_path / "lesson")
    program = write_program(tmp_path, "stops.py", "breakpoint()\n" + GOOD)
    graded = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(program)],
        capture_output=True, text=True, timeout=300, stdin=subprocess.PIPE,
    )  # fmt: skip
    assert graded.returncode == 0, graded.stdout + graded.stderr  # full marks: breakpoint() did nothing
    refused = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(program), "--debug"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert refused.returncode == 2 and "--debug" in refused.stderr
    served = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "serve", "--maze", "line-shared", "--debug"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert served.returncode == 2 and "--debug" in served.stderr


def test_what_a_brick_says_from_its_debugger_is_checked():
    """The brick is the student's: an event is cut to texts and numbers, short."""
    event = {
        "event": "stopped",
        "file": "p.py" * 1000,
        "line": "7",
        "thread": ["x"],
        "t_us": 2**70,
        "junk": 1,
    }
    kept = clean_debug_event(event)
    assert len(kept["file"]) == 2000 and kept["line"] == 0 and kept["thread"] == "['x']"
    assert "junk" not in kept
    assert clean_debug_event("nonsense")["event"] == "error"
    frames = clean_debug_event({"event": "stack", "frames": [{"file": "a", "line": 1}] * 500})["frames"]
    assert len(frames) == 64


@pytest.mark.skipif(shutil.which("tmux") is None, reason="tmux is not installed")
def test_a_breakpoint_session_in_a_real_terminal(folder):
    """As a student at a terminal: tmux runs `ev3sim2d run`, keys are typed at the prompt."""
    session = f"ev3sim2d-debug-{time.monotonic_ns()}"
    command = f"{sys.executable} -m ev3sim2d run prog.py --maze empty --time 5; sleep 30"
    subprocess.run(
        ["tmux", "new-session", "-d", "-s", session, "-x", "160", "-y", "40", "-c", str(folder), command],
        check=True,
    )
    try:

        def screen() -> str:
            return subprocess.run(
                ["tmux", "capture-pane", "-p", "-t", session], capture_output=True, text=True
            ).stdout

        def until(text: str) -> str:
            deadline = time.monotonic() + 60
            while text not in (shown := screen()):
                assert time.monotonic() < deadline, shown
                time.sleep(0.1)
            return shown

        until("(ev3sim2d)")  # (tmux shows no trailing space)
        subprocess.run(["tmux", "send-keys", "-t", session, "p speed * 3", "Enter"], check=True)
        until("(ev3sim2d) p speed * 3\n30\n")  # (the terminal echoes what was typed)
        subprocess.run(["tmux", "send-keys", "-t", session, "c", "Enter"], check=True)
        shown = until("ev3sim2d: finished")
        assert "] x 20 y " in shown
    finally:
        subprocess.run(["tmux", "kill-session", "-t", session], capture_output=True)
