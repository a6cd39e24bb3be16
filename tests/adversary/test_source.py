"""A student's source is parsed and compiled only inside its brick, under the brick's limits.

The grader used to compile every submission in its own process (and each worker again): a long
operator chain raised RecursionError there and ended the class run as an internal error, and a few
megabytes of valid source took the grader past a gigabyte.  Now the grader only looks at a program's
size (at most simulator/program.py's MAX_PROGRAM_BYTES), and a program its brick cannot compile is one
submission scoring 0, said once, beside honest ones graded as usual.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from ev3sim2d.simulator.program import MAX_PROGRAM_BYTES
from tests.grading.lesson_maker import GOOD, write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]
GRADE_MEASURING_ITSELF = """
import json, sys
from ev3sim2d.cli import main
code = main(sys.argv[1:])
try:
    import resource
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
except ImportError:  # (Windows)
    peak = None
print(json.dumps({"code": code, "grader_mb": peak}))
"""


def grade_measured(tmp_path: Path, *args) -> dict:
    """`ev3sim2d grade ARGS` in a process that says its exit status and its own peak memory (the
    grader's alone: its workers and bricks are other processes)."""
    done = subprocess.run(
        [sys.executable, "-c", GRADE_MEASURING_ITSELF, "grade", *map(str, args)],
        capture_output=True, text=True, cwd=ROOT, timeout=300,
        env={**os.environ, "EV3SIM2D_STATE_DIR": str(tmp_path / "state")},
    )  # fmt: skip
    said = json.loads(done.stdout.strip().splitlines()[-1])
    return {**said, "stderr": done.stderr, "stdout": done.stdout}


@pytest.fixture
def classroom(tmp_path) -> tuple[Path, Path]:
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "honest.py", GOOD)
    return lesson, tmp_path / "class"


@pytest.mark.parametrize(
    "source, said",
    [
        ("x = " + "1+" * 200_000 + "1\n", "RecursionError"),  # an operator chain: too deep for the parser
        ("x = " + "(" * 5_000 + ")" * 5_000 + "\n", "too many nested parentheses"),
        (
            "def f():\n"
            + "".join(f"{'    ' * (i + 1)}if 1:\n" for i in range(200))
            + "    " * 201
            + "pass\n",
            "too many",
        ),
        ("print('a' +)\n", "invalid syntax"),
    ],
    ids=["operator chain", "parentheses", "indentation", "syntax error"],
)
def test_a_source_that_cannot_be_compiled_is_one_submission_scoring_zero(classroom, tmp_path, source, said):
    lesson, folder = classroom
    (folder / "broken.py").write_text(source)
    done = grade_measured(tmp_path, lesson, folder, "--json", tmp_path / "r.json")
    assert done["code"] == 1, done["stderr"]  # a program scored less: not an internal error (4)
    results = {
        Path(s["submission"]).name: s for s in json.loads((tmp_path / "r.json").read_text())["submissions"]
    }
    assert results["honest.py"]["score"] == results["honest.py"]["max_score"]
    broken = results["broken.py"]
    assert broken["score"] == 0 and broken["status"] == "error" and said in broken["problem"]
    assert broken["problem"].count(said) == 1  # said once, not once per variant


def test_a_source_over_the_size_limit_is_refused_unread(classroom, tmp_path):
    """Megabytes of valid source: refused by its size before any process starts; the grader's memory
    stays where grading an honest class keeps it."""
    lesson, folder = classroom
    honest_only = grade_measured(tmp_path, lesson, folder)
    (folder / "huge.py").write_text("x = 1\n" * (3 * MAX_PROGRAM_BYTES // 6))
    done = grade_measured(tmp_path, lesson, folder, "--json", tmp_path / "r.json")
    assert done["code"] == 1, done["stderr"]
    huge = next(
        s for s in json.loads((tmp_path / "r.json").read_text())["submissions"] if "huge" in s["submission"]
    )
    assert huge["score"] == 0 and "more than a program may have" in huge["problem"]
    if done["grader_mb"] is not None:  # (ru_maxrss: KiB on Linux, bytes on macOS: either way not far above)
        assert done["grader_mb"] < honest_only["grader_mb"] * 1.2 + 50, (
            done["grader_mb"],
            honest_only["grader_mb"],
        )


def test_no_source_is_compiled_in_the_grader_or_its_workers(classroom, tmp_path, monkeypatch):
    """compile() as the grader and its (forked) workers see it is watched: it never meets a submission."""
    import builtins

    from ev3sim2d.grading.grader import grade
    from ev3sim2d.grading.lesson import load_lesson
    from ev3sim2d.grading.submission import find_submissions

    lesson_folder, folder = classroom
    (folder / "broken.py").write_text("print('a' +)\n")
    seen = tmp_path / "compiled"
    real_compile = builtins.compile

    def watched(source, filename, *args, **kwargs):
        if str(folder) in str(filename):
            with open(seen, "a") as log:
                log.write(f"{os.getpid()} {filename}\n")
        return real_compile(source, filename, *args, **kwargs)

    monkeypatch.setattr(builtins, "compile", watched)
    monkeypatch.setenv("EV3SIM2D_STATE_DIR", str(tmp_path / "state"))
    results = grade(load_lesson(lesson_folder), find_submissions([folder]), jobs=2).results
    assert [r.score for r in results] == [0, results[1].max_score]
    assert not seen.exists(), seen.read_text()
