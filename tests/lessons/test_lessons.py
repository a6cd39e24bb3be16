"""Every shipped lesson, graded by the grader itself: the solution gets full marks in every variant,
the starter does not, and each typical wrong program loses points on the check its docstring names
(`Loses: check, check`).  Each lesson is graded once (all its programs, two at a time)."""

import ast
import re
from pathlib import Path

import pytest

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import list_shipped_lessons, load_lesson, shipped_lessons_dir
from ev3sim2d.grading.submission import find_submissions

LESSONS = list_shipped_lessons()
REQUIRED = [
    "square",
    "wall-stop",
    "bump-turn",
    "gyro-turn",
    "line-follow",
    "line-gap",
    "maze",
    "find-color",
    "odometry",
]
_graded: dict[str, dict] = {}


def wrong_programs(lesson_id: str) -> list[Path]:
    return sorted((shipped_lessons_dir() / lesson_id / "wrong").glob("*.py"))


def named_losses(path: Path) -> list[str]:
    """The checks a wrong program's docstring says it loses."""
    doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    match = re.search(r"^Loses:\s*(.+)$", doc, re.MULTILINE)
    assert match, f"{path}: its docstring must say `Loses: CHECK[, CHECK]`"
    return [name.strip() for name in match.group(1).split(",")]


def graded(lesson_id: str) -> dict:
    """{program file name or wrong/NAME: SubmissionResult} for every program of the lesson."""
    if lesson_id not in _graded:
        lesson = load_lesson(lesson_id)
        programs = [lesson.solution, lesson.starter, *wrong_programs(lesson_id)]
        results = grade(lesson, find_submissions(programs), jobs=2).results
        names = ["solution", "starter", *[f"wrong/{p.name}" for p in wrong_programs(lesson_id)]]
        _graded[lesson_id] = dict(zip(names, results, strict=True))
    return _graded[lesson_id]


def test_the_required_lessons_are_shipped():
    assert set(REQUIRED) <= set(LESSONS)


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_a_lesson_has_its_files_and_variants(lesson_id):
    lesson = load_lesson(lesson_id)
    for name in ("README.md", "starter.py", "solution.py"):
        assert (lesson.folder / name).is_file(), name
    assert len(lesson.variants) >= 2
    assert any(v.hidden for v in lesson.variants), "at least one hidden variant"
    assert len(wrong_programs(lesson_id)) >= 2, "at least two typical wrong programs"


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_readme_shows_the_visible_variants_only(lesson_id):
    lesson = load_lesson(lesson_id)
    readme = (lesson.folder / "README.md").read_text()
    for variant in lesson.variants:
        mentioned = re.search(rf"`{re.escape(variant.name)}`|\b{re.escape(variant.name)}\.png\b", readme)
        if variant.hidden:
            assert not mentioned, f"hidden variant {variant.name} is in the README"
        else:
            assert mentioned, f"visible variant {variant.name} is not in the README"
            assert (lesson.folder / f"{variant.name}.png").is_file()
    for check in lesson.checks:
        assert f"`{check.name}`" in readme, f"the README does not explain check {check.name}"


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_programs_are_plain_ev3dev2_programs(lesson_id):
    folder = shipped_lessons_dir() / lesson_id
    for path in [folder / "starter.py", folder / "solution.py", *wrong_programs(lesson_id)]:
        tree = ast.parse(path.read_text())
        modules = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
        modules |= {
            n.module.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module
        }
        assert "ev3sim2d" not in modules, path
        assert "ev3dev2" in modules, path


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_solution_gets_full_marks_in_every_variant(lesson_id):
    result = graded(lesson_id)["solution"]
    for variant in result.variants:
        failed = [f"{c.name}: {c.message}" for c in variant.failed_checks()]
        assert variant.status == "graded" and not failed, f"{variant.name}: {variant.message}; {failed}"
    assert result.full_marks


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_starter_runs_but_does_not_solve_the_task(lesson_id):
    result = graded(lesson_id)["starter"]
    assert result.status == "graded", result.first_failure()
    assert result.score < result.max_score


@pytest.mark.parametrize(
    "lesson_id, program", [(lesson, p.name) for lesson in LESSONS for p in wrong_programs(lesson)]
)
def test_a_wrong_program_loses_points_on_the_check_that_names_its_mistake(lesson_id, program):
    result = graded(lesson_id)[f"wrong/{program}"]
    lesson_checks = {c.name for c in load_lesson(lesson_id).checks}
    for name in named_losses(shipped_lessons_dir() / lesson_id / "wrong" / program):
        assert name in lesson_checks, f"{program} names {name!r}, not a check of {lesson_id}"
        lost = [v.name for v in result.variants for c in v.checks if c.name == name and not c.passed]
        assert lost, f"{program} should lose points on {name!r} in some variant"
    assert result.score < result.max_score
