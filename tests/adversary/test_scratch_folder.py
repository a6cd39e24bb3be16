"""A brick's scratch folder is the program's: nothing in it is opened by name, however it is shaped.

The simulator used to read a brick's console by its path when the program ended without a word, and
removed the folder with shutil.rmtree.  A program that replaced its console with a link to
/proc/self/environ put the grader's environment (with its tokens) into the report; a link to /dev/zero
made the worker read until the machine ran out of memory; 3000 nested folders made the clean-up raise
RecursionError and end the whole class run as an internal error, leaving the temporary folder behind.
Each attack here ends its program the way that made the simulator read the console (an exit without a
word), and the run, the report and the clean-up must be as for an honest program.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.grading.lesson_maker import GOOD, write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]
SECRET = "ev3sim2d-test-secret-4f9a1c"
END_WITHOUT_A_WORD = "import posix\nposix._exit(5)  # (os._exit is the brick's: posix's ends the process)\n"
# the console is in the scratch folder (HOME), beside the copy of the program's folder it works in
CONSOLE = "import os\nos.chdir(os.environ['HOME'])\nos.remove('console.log')\n"
ATTACKS = {
    "console to environ": CONSOLE + "os.symlink('/proc/self/environ', 'console.log')\n",
    "console to the simulator's environ": (
        CONSOLE + "os.symlink(f'/proc/{os.getppid()}/environ', 'console.log')\n"
    ),
    "console to /dev/zero": CONSOLE + "os.symlink('/dev/zero', 'console.log')\n",
    "console to a fifo": CONSOLE + "os.mkfifo('console.log')\n",
    "console to its own fd": CONSOLE + "os.symlink('/proc/self/fd/1', 'console.log')\n",
    "3000 nested folders": (
        "import os\nfor _ in range(3000):\n    os.mkdir('a')\n    open('a/f', 'w').close()\n    os.chdir('a')\n"
    ),
    "unreadable folders": (
        "import os\nfor name in 'xyz':\n    os.makedirs(name + '/in')\n    open(name + '/in/f', 'w').close()\n"
        "    os.chmod(name + '/in', 0)\n    os.chmod(name, 0)\n"
    ),
    "a link out of the folder": "import os\nos.symlink(os.environ.get('OUTSIDE', '/etc'), 'out')\n",
}
needs_posix = pytest.mark.skipif(
    not hasattr(os, "symlink") or not hasattr(os, "mkfifo"), reason="POSIX files"
)


@pytest.fixture
def temporary(tmp_path) -> Path:
    """The temporary folder the simulator makes scratch folders in: empty again after each run."""
    folder = tmp_path / "tmp"
    folder.mkdir()
    return folder


def run(program: Path, temporary: Path, outside: Path) -> subprocess.CompletedProcess:
    env = {**os.environ, "TMPDIR": str(temporary), "EV3SIM2D_SECRET": SECRET, "OUTSIDE": str(outside)}
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "5", "--summary", str(program) + ".json"],
        capture_output=True, text=True, cwd=ROOT, env=env, timeout=120,
    )  # fmt: skip


@needs_posix
@pytest.mark.parametrize("attack", list(ATTACKS))
def test_what_a_program_does_to_its_scratch_folder_never_reaches_the_simulator(tmp_path, temporary, attack):
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "keep.txt").write_text("keep")
    program = tmp_path / "attack.py"
    program.write_text(ATTACKS[attack] + "print('done')\n" + END_WITHOUT_A_WORD)
    done = run(program, temporary, outside)
    assert done.returncode == 1, done.stderr  # a program that ended without a word: not an internal error
    assert "ended without a word (exit status 5" in done.stderr, done.stderr
    assert SECRET not in done.stdout + done.stderr + Path(str(program) + ".json").read_text()
    assert "Traceback" not in done.stderr
    assert list(temporary.iterdir()) == [], "the scratch folder was left behind"
    assert (outside / "keep.txt").read_text() == "keep"


@needs_posix
def test_a_class_run_grades_every_attacker_and_cleans_up(tmp_path, temporary):
    """Every attack above in one class, graded: each scores 0, the honest program full marks, the run
    ends as a class run does (not an internal error), and nothing of it is left in the temporary folder."""
    lesson = write_lesson(tmp_path / "lesson")
    folder = tmp_path / "class"
    write_program(folder, "honest.py", GOOD)
    for number, source in enumerate(ATTACKS.values()):
        write_program(folder, f"attack{number}.py", source + END_WITHOUT_A_WORD)
    env = {
        **os.environ,
        "TMPDIR": str(temporary),
        "EV3SIM2D_SECRET": SECRET,
        "EV3SIM2D_STATE_DIR": str(tmp_path),
    }
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(folder), "--json", str(tmp_path / "r.json")],
        capture_output=True, text=True, cwd=ROOT, env=env, timeout=600,
    )  # fmt: skip
    assert done.returncode == 1, done.stderr
    report = (tmp_path / "r.json").read_text()
    assert SECRET not in done.stdout + done.stderr + report
    scores = {Path(s["submission"]).name: s["score"] for s in json.loads(report)["submissions"]}
    assert scores.pop("honest.py") == 10 and set(scores.values()) == {0}
    assert list(temporary.iterdir()) == []
