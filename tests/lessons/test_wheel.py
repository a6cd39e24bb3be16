"""The wheel students install ships the lessons without what must stay with the teacher: no hidden
variant (a lesson's hidden/ folder), no reference solution, no deliberately wrong program; and the
lessons it ships still load from its copy (with their visible variants only)."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from tests.installed import installed_venv

ROOT = Path(__file__).resolve().parents[2]
LESSONS = sorted(p.parent.name for p in (ROOT / "lessons").glob("*/lesson.yaml"))


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    """The wheel the installed-package tests use (.ci/run built it), else one built here the same way."""
    found = installed_venv.from_environment()
    return found.wheel if found else installed_venv.build_wheel(tmp_path_factory.mktemp("wheel"))


@pytest.fixture(scope="module")
def unpacked(wheel, tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("unpacked")
    with zipfile.ZipFile(wheel) as archive:
        archive.extractall(folder)
    return folder


def test_the_wheel_ships_every_lesson_but_no_hidden_variant_solution_or_wrong_program(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    lessons = [name for name in names if name.startswith("ev3sim2d/_lessons/")]
    for lesson_id in LESSONS:
        assert f"ev3sim2d/_lessons/{lesson_id}/lesson.yaml" in lessons
        assert f"ev3sim2d/_lessons/{lesson_id}/starter.py" in lessons
        assert f"ev3sim2d/_lessons/{lesson_id}/starter_pybricks.py" in lessons
        assert f"ev3sim2d/_lessons/{lesson_id}/README.md" in lessons
    leaks = [
        name
        for name in lessons
        if "/hidden/" in name
        or name.endswith("/hidden.yaml")
        or "/wrong/" in name
        or name.endswith(("/solution.py", "/solution_pybricks.py"))
    ]
    assert not leaks
    hidden_worlds = {p.name for p in (ROOT / "lessons").glob("*/hidden/*")}
    assert not [name for name in lessons if Path(name).name in hidden_worlds]


def test_the_shipped_lessons_load_from_the_wheels_copy(unpacked):
    """In a fresh interpreter that finds ev3sim2d in the unpacked wheel only (not in this checkout)."""
    script = (
        "import sys\n"
        "from ev3sim2d.grading.lesson import list_shipped_lessons, load_lesson, shipped_lessons_dir\n"
        f"assert str(shipped_lessons_dir()).startswith({str(unpacked)!r}), shipped_lessons_dir()\n"
        "for lesson_id in list_shipped_lessons():\n"
        "    lesson = load_lesson(lesson_id)\n"
        "    assert lesson.variants and not lesson.hidden_variants() and lesson.solution is None\n"
        "    assert lesson.solution_pybricks is None and lesson.starter_pybricks is not None\n"
        "    print(lesson_id, len(lesson.variants))\n"
    )
    env = {**os.environ, "PYTHONPATH": str(unpacked)}
    loaded = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300, env=env, cwd=unpacked
    )
    assert loaded.returncode == 0, loaded.stdout + loaded.stderr
    assert sorted(line.split()[0] for line in loaded.stdout.splitlines()) == LESSONS
