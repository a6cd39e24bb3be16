"""`ev3sim2d grade` as a teacher or a CI job runs it: output, files, exit status."""

import json
import subprocess
import sys
from pathlib import Path

from .lesson_maker import GOOD, HIDDEN, SHORT, write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]


def grade_cli(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd or ROOT,
        timeout=300,
    )


def test_one_program_that_passes_exits_0_with_its_details(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    prog = write_program(tmp_path, "good.py", GOOD)
    result = grade_cli(
        lesson,
        prog,
        "--json",
        tmp_path / "r.json",
        "--junit",
        tmp_path / "r.xml",
        "--csv",
        tmp_path / "r.csv",
    )
    assert result.returncode == 0, result.stderr
    assert "good.py: 10/10 (graded)" in result.stdout and "PASS reach (3/3, goal)" in result.stdout
    assert json.loads((tmp_path / "r.json").read_text())["submissions"][0]["score"] == 10
    assert (tmp_path / "r.xml").read_text().startswith("<?xml")
    assert (tmp_path / "r.csv").read_bytes().startswith(b"\xef\xbb\xbfsubmission,status,score")  # BOM: Excel


def test_one_program_that_fails_exits_1(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    prog = write_program(tmp_path, "short.py", SHORT)
    result = grade_cli(lesson, prog)
    assert result.returncode == 1
    assert "FAIL reach (0/3, goal)" in result.stdout
    assert "---- finished (0/1): counts only once the robot reaches the goal" in result.stdout
    assert grade_cli(lesson, prog, "--pass-percent", "0").returncode == 0


def test_a_class_prints_a_table_and_exits_1_when_a_student_misses_marks(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "alice.py", GOOD)
    write_program(tmp_path / "class", "bob.py", SHORT)
    result = grade_cli(lesson, tmp_path / "class", "--jobs", "2")
    assert result.returncode == 1, result.stderr
    assert "1 of 2 submission(s) scored below 100%" in result.stderr
    assert "2 submission(s), 1 with full marks" in result.stdout
    assert "[1/2]" in result.stderr and "[2/2]" in result.stderr


def kept_videos(folder: Path) -> list[str]:
    return sorted(p.relative_to(folder).as_posix() for p in folder.rglob("*.*"))


def test_videos_keep_what_happened_in_failed_visible_variants(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "alice.py", GOOD)
    write_program(tmp_path / "class", "bob.py", SHORT)
    result = grade_cli(lesson, tmp_path / "class", "--videos", tmp_path / "videos")
    assert result.returncode == 1, result.stderr  # bob misses marks
    kept = kept_videos(tmp_path / "videos")
    assert not any(name.startswith("alice") for name in kept)
    assert any(name.startswith("bob/room.") for name in kept)
    assert not any("hidden" in name for name in kept)  # a video would show the hidden world


def test_hidden_variants_videos_only_when_the_teacher_asks(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    prog = write_program(tmp_path, "bob.py", SHORT)
    result = grade_cli(lesson, prog, "--videos", tmp_path / "videos", "--hidden-videos")
    assert result.returncode == 1, result.stderr
    kept = kept_videos(tmp_path / "videos")
    assert any(name.startswith("bob/room.") for name in kept)
    assert any(name.startswith("bob/hidden-room.") for name in kept)
    alone = grade_cli(lesson, prog, "--hidden-videos")
    assert alone.returncode == 2 and "--hidden-videos needs --videos DIR" in alone.stderr


def test_hidden_variants_from_a_teachers_private_folder(tmp_path):
    lesson = write_lesson(tmp_path / "lesson", hidden_text=None)
    prog = write_program(tmp_path, "good.py", GOOD)
    visible_only = grade_cli(lesson, prog)
    assert visible_only.returncode == 0 and "good.py: 5/5 (graded)" in visible_only.stdout
    assert "grading its visible variants only" in visible_only.stderr
    private = tmp_path / "private" / "lesson"
    private.mkdir(parents=True)
    (private / "hidden.yaml").write_text(HIDDEN)
    result = grade_cli(lesson, prog, "--hidden", tmp_path / "private")
    assert result.returncode == 0, result.stderr
    assert "good.py: 10/10 (graded)" in result.stdout and "hidden variant 1: 5/5, passed" in result.stdout
    assert "hidden-room" not in result.stdout + result.stderr
    missing = grade_cli(lesson, prog, "--hidden", tmp_path / "nowhere")
    assert missing.returncode == 2 and "no hidden.yaml for lesson 'lesson' here" in missing.stderr


def test_a_broken_lesson_exits_2_with_file_and_line(tmp_path):
    lesson = write_lesson(
        tmp_path / "lesson", lesson_text="title: x\ngoal: y\ntime_s: -1\nvariants: []\nchecks: []\n"
    )
    result = grade_cli(lesson, tmp_path / "prog.py")
    assert result.returncode == 2
    assert "lesson.yaml:3:9: 'time_s' must be more than 0" in result.stderr


def test_a_shipped_lesson_by_name(tmp_path):
    result = grade_cli("wall-stop", ROOT / "lessons" / "wall-stop" / "solution.py", "--quiet")
    assert result.returncode == 0, result.stdout + result.stderr
    assert "40/40 (graded)" in result.stdout  # the hidden variants of the checkout are graded
    assert "hidden variant 3: 10/10, passed" in result.stdout
    assert not any(f"{name}:" in result.stdout for name in ("near", "across", "noisy"))


def test_a_broken_check_of_the_lessons_own_stops_grading_loudly(tmp_path):
    from .lesson_maker import LESSON

    lesson = write_lesson(
        tmp_path / "lesson", lesson_text=LESSON.format(time_s=5, extra="") + "  - {kind: broken, points: 1}\n"
    )
    (lesson / "check_broken.py").write_text(
        "from ev3sim2d.grading.check import Check\n\n"
        "class Broken(Check):\n"
        "    KIND = 'broken'\n"
        "    SUMMARY = 'raises'\n\n"
        "    def evaluate(self, run):\n"
        "        return 1 / 0\n"
    )
    result = grade_cli(lesson, write_program(tmp_path, "good.py", GOOD))
    assert result.returncode == 2
    assert "a check failed while scoring" in result.stderr and "ZeroDivisionError" in result.stderr
