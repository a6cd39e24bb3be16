"""What the wheel students install holds: everything a user's first steps need (worlds, robots, example
programs, the lessons' student side), and nothing of what a teacher keeps from students (a lesson's
hidden variants and their worlds, its reference solution, its deliberately wrong programs)."""

import zipfile
from pathlib import Path

from tests.installed.installed_venv import ROOT

KEPT_FROM_STUDENTS = ("hidden", "hidden.yaml", "solution.py", "solution_pybricks.py", "wrong")


def test_the_wheel_holds_no_hidden_variant_solution_or_wrong_program_anywhere(installed):
    names = zipfile.ZipFile(installed.wheel).namelist()
    leaks = [name for name in names if set(Path(name).parts) & set(KEPT_FROM_STUDENTS)]
    assert not leaks, f"the wheel gives students what the teacher keeps: {leaks}"
    teachers_files = {
        path.name
        for lesson in (ROOT / "lessons").iterdir()
        for kept in KEPT_FROM_STUDENTS
        for path in ([lesson / kept] if (lesson / kept).is_file() else (lesson / kept).rglob("*"))
        if path.is_file()
    }
    assert teachers_files, "the repository's lessons keep hidden variants, solutions and wrong programs"
    lessons = [name for name in names if name.startswith("ev3sim2d/_lessons/")]
    assert not [name for name in lessons if Path(name).name in teachers_files - {"README.md", "lesson.yaml"}]


def test_the_wheel_holds_the_worlds_robots_and_examples_a_user_starts_with(installed):
    names = set(zipfile.ZipFile(installed.wheel).namelist())
    for path in (ROOT / "mazes").glob("*.yaml"):
        assert f"ev3sim2d/_mazes/{path.name}" in names
    for path in (ROOT / "examples").rglob("*.py"):
        assert f"ev3sim2d/_examples/{path.relative_to(ROOT / 'examples').as_posix()}" in names
    for lesson in (ROOT / "lessons").glob("*/lesson.yaml"):
        for student_file in ("lesson.yaml", "README.md", "starter.py", "starter_pybricks.py"):
            assert f"ev3sim2d/_lessons/{lesson.parent.name}/{student_file}" in names


def test_the_wheel_installs_no_top_level_shim_only_its_copies_for_the_bricks(installed):
    """A student's Python keeps its own `pybricks` (LEGO's stubs, for an editor's completion) and its own
    python-ev3dev2: the wheel puts both shims under ev3sim2d/_shim/, where only a brick looks."""
    names = zipfile.ZipFile(installed.wheel).namelist()
    assert {name.split("/")[0] for name in names if not name.split("/")[0].endswith(".dist-info")} == {
        "ev3sim2d"
    }
    for shim in ("ev3dev2", "pybricks"):
        for path in (ROOT / shim).rglob("*.py"):
            assert f"ev3sim2d/_shim/{path.relative_to(ROOT).as_posix()}" in names
