"""The folder a grader runs in is the student's: nothing committed there counts, runs, or is written through.

GitHub Classroom (and a teacher grading inside a cloned repository) runs `ev3sim2d grade LESSON
main.py --json grade.json` in the student's checkout.  A student commits what they like into it: a
results file with full marks, a folder named like the lesson with checks of its own, links at the
names the grader writes.  Each attack is played against the real command, in a checkout of its own,
beside an honest program: the attacker scores 0 (or what its program earns), the honest program full
marks, nothing outside the outputs is written, and the outputs are regular files.
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
PRINTS_ONLY = "print('I am done')\n"
LESSON = "reach-goal"
needs_links = pytest.mark.skipif(
    not hasattr(os, "symlink") or not hasattr(os, "O_NOFOLLOW"), reason="no links here"
)


@pytest.fixture
def teacher(tmp_path, monkeypatch) -> Path:
    """The teacher's folder of lessons (outside any checkout), and a state folder of this test's own."""
    monkeypatch.setenv("EV3SIM2D_STATE_DIR", str(tmp_path / "state"))
    write_lesson(tmp_path / "lessons" / LESSON)
    return tmp_path / "lessons"


@pytest.fixture
def checkout(tmp_path) -> Path:
    folder = tmp_path / "checkout"
    folder.mkdir()
    return folder


def grade(checkout: Path, teacher: Path, *args) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", LESSON, "--lessons", str(teacher), *map(str, args)],
        capture_output=True,
        text=True,
        cwd=checkout,
        timeout=300,
        env=os.environ.copy(),
    )


def scores(path: Path) -> dict[str, int]:
    data = json.loads(path.read_text())
    return {Path(s["submission"]).name: s["score"] for s in data["submissions"]}


def test_a_committed_results_file_with_full_marks_counts_for_nothing(teacher, checkout):
    write_program(checkout, "main.py", PRINTS_ONLY)
    forged = {
        "format": "ev3sim2d-grades-1",
        "lesson": LESSON,
        "submissions": [
            {
                "submission": "main.py",
                "key": "x",
                "score": 5,
                "max_score": 5,
                "status": "graded",
                "variants": [],
            }
        ],
    }
    (checkout / "grade.json").write_text(json.dumps(forged))
    for resume in ([], ["--resume"]):
        done = grade(checkout, teacher, "main.py", "--json", "grade.json", *resume)
        assert done.returncode == 1, done.stderr
        assert scores(checkout / "grade.json") == {"main.py": 0}
        (checkout / "grade.json").write_text(json.dumps(forged))


def test_a_results_file_signed_here_is_taken_again_only_with_resume_and_unchanged(teacher, checkout):
    write_program(checkout, "main.py", GOOD)
    assert grade(checkout, teacher, "main.py", "--json", "grade.json").returncode == 0
    resumed = grade(checkout, teacher, "main.py", "--json", "grade.json", "--resume")
    assert "1 result(s) taken from grade.json" in resumed.stderr
    data = json.loads((checkout / "grade.json").read_text())
    data["submissions"][0]["score"] = 9  # tampered with: its signature fails, so it is graded again
    (checkout / "grade.json").write_text(json.dumps(data))
    again = grade(checkout, teacher, "main.py", "--json", "grade.json", "--resume")
    assert "taken from" not in again.stderr and scores(checkout / "grade.json") == {"main.py": 10}


def test_a_folder_named_like_the_lesson_in_the_checkout_is_not_the_lesson(teacher, checkout, tmp_path):
    """The student's own `reach-goal/` with an easy lesson and a check_*.py that would run inside the
    grader (it writes a marker and copies the grader's environment) is never read."""
    marker = tmp_path / "the-students-check-ran"
    planted = write_lesson(
        checkout / LESSON, lesson_text="title: Easy\ngoal: Nothing.\ntime_s: 1\nvariants: []\nchecks: []\n"
    )
    (planted / "check_evil.py").write_text(
        f"import os\nopen({str(marker)!r}, 'w').write(repr(dict(os.environ)))\n"
    )
    write_program(checkout, "main.py", PRINTS_ONLY)
    done = grade(checkout, teacher, "main.py", "--json", "grade.json")
    assert done.returncode == 1 and scores(checkout / "grade.json") == {"main.py": 0}
    assert not marker.exists()
    named = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", LESSON, "main.py"],
        capture_output=True,
        text=True,
        cwd=checkout,
    )
    assert named.returncode == 2 and f"write ./{LESSON}" in named.stderr  # not shipped: said, not taken


@needs_links
@pytest.mark.parametrize(
    "name", ["grade.json", "grade.json.part", "grade.xml", "grade.xml.part", "grade.csv", "grade.csv.part"]
)
def test_links_planted_at_output_names_are_replaced_not_written_through(teacher, checkout, tmp_path, name):
    victim = tmp_path / "teachers-file"
    victim.write_text("precious")
    (checkout / name).symlink_to(victim)
    write_program(checkout, "main.py", GOOD)
    done = grade(
        checkout, teacher, "main.py", "--json", "grade.json", "--junit", "grade.xml", "--csv", "grade.csv"
    )
    assert done.returncode == 0, done.stderr
    assert victim.read_text() == "precious"
    for output in ("grade.json", "grade.xml", "grade.csv"):
        assert (checkout / output).is_file() and not (checkout / output).is_symlink()
    assert scores(checkout / "grade.json") == {"main.py": 10}  # (two variants of 5 points)


@needs_links
def test_a_fifo_or_a_link_to_a_device_at_an_output_name_neither_hangs_nor_is_used(teacher, checkout):
    os.mkfifo(checkout / "grade.json")
    (checkout / "grade.xml").symlink_to("/dev/null")
    write_program(checkout, "main.py", GOOD)
    done = grade(checkout, teacher, "main.py", "--json", "grade.json", "--junit", "grade.xml")
    assert done.returncode == 0, done.stderr
    assert (checkout / "grade.json").is_file() and (checkout / "grade.xml").is_file()


@needs_links
def test_a_linked_folder_for_videos_is_refused_not_written_into(teacher, checkout, tmp_path):
    """--videos DIR/<submission>/: a link planted at the submission's folder name would put the videos
    where it points."""
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (checkout / "videos").mkdir()
    (checkout / "videos" / "main").symlink_to(elsewhere)
    write_program(checkout, "main.py", PRINTS_ONLY)
    grade(checkout, teacher, "main.py", "--videos", "videos")
    assert list(elsewhere.iterdir()) == []


@needs_links
def test_the_classroom_output_file_is_appended_to_only_if_it_is_a_regular_file(teacher, checkout, tmp_path):
    victim = tmp_path / "teachers-file"
    victim.write_text("precious\n")
    (checkout / "out.txt").symlink_to(victim)
    write_program(checkout, "main.py", GOOD)
    done = grade(checkout, teacher, "main.py", "--classroom", "out.txt")
    assert done.returncode == 2 and "could not write the results" in done.stderr
    assert victim.read_text() == "precious\n"
    (checkout / "out.txt").unlink()
    (checkout / "out.txt").write_text("earlier=1\n")
    assert grade(checkout, teacher, "main.py", "--classroom", "out.txt").returncode == 0
    lines = (checkout / "out.txt").read_text().splitlines()
    assert lines[0] == "earlier=1" and lines[1].startswith("result=")
