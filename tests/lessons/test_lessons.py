"""Every lesson of the repository, graded by the grader itself: the solution gets full marks in every
variant (hidden ones too), each typical wrong program loses points on the check its docstring names
(`Loses: check, check`), and a program that does not solve the task (one that does nothing, only prints,
only spins on the spot, drives straight ahead for ever, or the starter) scores nothing.  The same holds
for the lesson's Pybricks 2.0 programs (starter_pybricks.py, solution_pybricks.py: LEGO's EV3
MicroPython, which the brick runs with the pybricks shim).  Each lesson is graded once (all its
programs, two at a time)."""

import ast
import re
from pathlib import Path

import pytest
import yaml

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import HIDDEN_DIR, HIDDEN_FILE, LESSON_FILE, list_shipped_lessons, load_lesson
from ev3sim2d.grading.submission import find_submissions
from ev3sim2d.world.maze_file import shipped_mazes_dir

LESSONS_DIR = Path(__file__).resolve().parents[2] / "lessons"  # the repository's: with hidden/, solutions
LESSONS = sorted(p.parent.name for p in LESSONS_DIR.glob(f"*/{LESSON_FILE}"))
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
    "convoy",
]
DRIVE = """\
import time
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on(SpeedPercent({left}), SpeedPercent({right}))
while True:
    time.sleep(0.1)
"""
DOES_NOT_SOLVE = {
    "does_nothing.py": "",
    "only_prints.py": 'print("hello")\n',
    "spins_in_place.py": DRIVE.format(left=30, right=-30),
    "drives_straight_for_ever.py": DRIVE.format(left=30, right=30),
}
NOT_SOLVING = [*DOES_NOT_SOLVE, "starter", "starter_pybricks"]
_graded: dict[str, dict] = {}


def lesson_dir(lesson_id: str) -> Path:
    return LESSONS_DIR / lesson_id


def wrong_programs(lesson_id: str) -> list[Path]:
    return sorted((lesson_dir(lesson_id) / "wrong").glob("*.py"))


def named_losses(path: Path) -> list[str]:
    """The checks a wrong program's docstring says it loses."""
    doc = ast.get_docstring(ast.parse(path.read_text())) or ""
    match = re.search(r"^Loses:\s*(.+)$", doc, re.MULTILINE)
    assert match, f"{path}: its docstring must say `Loses: CHECK[, CHECK]`"
    return [name.strip() for name in match.group(1).split(",")]


@pytest.fixture(scope="module")
def not_solving_folder(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("not-solving")
    for name, source in DOES_NOT_SOLVE.items():
        (folder / name).write_text(source)
    return folder


def graded(lesson_id: str, not_solving: Path) -> dict:
    """{"solution", "starter", "wrong/NAME" or a DOES_NOT_SOLVE name: SubmissionResult} for the lesson."""
    if lesson_id not in _graded:
        lesson = load_lesson(lesson_dir(lesson_id))
        trivial = [not_solving / name for name in DOES_NOT_SOLVE]
        pybricks = [lesson.solution_pybricks, lesson.starter_pybricks]
        programs = [lesson.solution, lesson.starter, *pybricks, *wrong_programs(lesson_id), *trivial]
        results = grade(lesson, find_submissions(programs), jobs=2).results
        names = [
            "solution",
            "starter",
            "solution_pybricks",
            "starter_pybricks",
            *[f"wrong/{p.name}" for p in wrong_programs(lesson_id)],
            *DOES_NOT_SOLVE,
        ]
        _graded[lesson_id] = dict(zip(names, results, strict=True))
    return _graded[lesson_id]


def test_the_required_lessons_are_shipped():
    assert set(REQUIRED) <= set(LESSONS)
    assert set(REQUIRED) <= set(list_shipped_lessons())


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_a_lesson_has_its_files_and_variants(lesson_id):
    lesson = load_lesson(lesson_dir(lesson_id))
    for name in ("README.md", "starter.py", "solution.py", "starter_pybricks.py", "solution_pybricks.py"):
        assert (lesson.folder / name).is_file(), name
    assert lesson.starter_pybricks == lesson.folder / "starter_pybricks.py"
    assert lesson.solution_pybricks == lesson.folder / "solution_pybricks.py"
    assert len(lesson.variants) >= 2
    assert lesson.hidden_variants(), "at least one hidden variant"
    assert lesson.hidden_file == lesson.folder / HIDDEN_DIR / HIDDEN_FILE
    assert len(wrong_programs(lesson_id)) >= 2, "at least two typical wrong programs"


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_every_check_says_whether_it_is_a_goal(lesson_id):
    data = yaml.safe_load((lesson_dir(lesson_id) / LESSON_FILE).read_text())
    for check in data["checks"]:
        assert isinstance(check.get("goal"), bool), (
            f"check {check.get('name')} does not say `goal: true|false`"
        )
    assert load_lesson(lesson_dir(lesson_id)).goal_checks


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_readme_shows_the_visible_variants_only(lesson_id):
    lesson = load_lesson(lesson_dir(lesson_id))
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
def test_what_only_hidden_variants_need_lives_in_the_hidden_folder(lesson_id):
    lesson = load_lesson(lesson_dir(lesson_id))
    hidden_dir = lesson.folder / HIDDEN_DIR

    def needs(variant) -> list[Path]:
        robot = variant.robot.source if variant.robot is not None else None
        return [Path(p).resolve() for p in (variant.world_path, robot) if p is not None]

    public = {path for variant in lesson.visible_variants() for path in needs(variant)}
    only_hidden = []
    for variant in lesson.hidden_variants():
        for path in needs(variant):
            if (
                path in public
                or path.is_relative_to(shipped_mazes_dir())
                or not path.is_relative_to(lesson.folder)
            ):
                continue
            assert path.is_relative_to(hidden_dir), (
                f"{path.name}, needed by a hidden variant only, is not in hidden/"
            )
            only_hidden.append(path.name)
    public_text = [p for p in lesson.folder.rglob("*") if p.is_file() and not p.is_relative_to(hidden_dir)]
    for path in public_text:
        if path.suffix in (".md", ".yaml", ".py"):
            text = path.read_text()
            for name in only_hidden:
                assert name not in text, (
                    f"{path.relative_to(lesson.folder)} names the hidden world file {name}"
                )


def imported_modules(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    modules = {a.name.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.Import) for a in n.names}
    return modules | {
        n.module.split(".")[0] for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module
    }


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_programs_are_plain_ev3dev2_programs(lesson_id):
    folder = lesson_dir(lesson_id)
    for path in [folder / "starter.py", folder / "solution.py", *wrong_programs(lesson_id)]:
        modules = imported_modules(path)
        assert "ev3sim2d" not in modules, path
        assert "ev3dev2" in modules, path


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_pybricks_programs_are_plain_pybricks_programs(lesson_id):
    """What runs on an EV3 with LEGO's EV3 MicroPython image: pybricks and MicroPython's modules only."""
    folder = lesson_dir(lesson_id)
    for path in [folder / "starter_pybricks.py", folder / "solution_pybricks.py"]:
        modules = imported_modules(path)
        assert "pybricks" in modules, path
        assert modules <= {"pybricks", "math", "time", "random"}, f"{path}: {modules}"
        assert path.read_text().startswith("#!/usr/bin/env pybricks-micropython\n"), path


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_solution_gets_full_marks_in_every_variant(lesson_id, not_solving_folder):
    result = graded(lesson_id, not_solving_folder)["solution"]
    assert len(result.variants) == len(load_lesson(lesson_dir(lesson_id)).variants)
    for variant in result.variants:
        failed = [f"{c.name}: {c.message}" for c in variant.failed_checks()]
        assert variant.status == "graded" and not failed, f"{variant.name}: {variant.message}; {failed}"
    assert result.full_marks


@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_pybricks_solution_gets_full_marks_in_every_variant(lesson_id, not_solving_folder):
    result = graded(lesson_id, not_solving_folder)["solution_pybricks"]
    assert len(result.variants) == len(load_lesson(lesson_dir(lesson_id)).variants)
    for variant in result.variants:
        failed = [f"{c.name}: {c.message}" for c in variant.failed_checks()]
        assert variant.status == "graded" and not failed, f"{variant.name}: {variant.message}; {failed}"
    assert result.full_marks


@pytest.mark.parametrize("starter", ["starter", "starter_pybricks"])
@pytest.mark.parametrize("lesson_id", LESSONS)
def test_the_starter_runs(lesson_id, starter, not_solving_folder):
    result = graded(lesson_id, not_solving_folder)[starter]
    assert result.status == "graded", result.first_failure()


@pytest.mark.parametrize("program", NOT_SOLVING)
@pytest.mark.parametrize("lesson_id", LESSONS)
def test_a_program_that_does_not_solve_the_task_scores_nothing(lesson_id, program, not_solving_folder):
    result = graded(lesson_id, not_solving_folder)[program]
    earned = [f"{v.name}: {c.name}: {c.message}" for v in result.variants for c in v.checks if c.points]
    assert result.score == 0, earned
    goals = [c for v in result.variants for c in v.checks if c.goal]
    assert goals and not any(c.passed for c in goals), "a goal check passes without the task being solved"


@pytest.mark.parametrize(
    "lesson_id, program", [(lesson, p.name) for lesson in LESSONS for p in wrong_programs(lesson)]
)
def test_a_wrong_program_loses_points_on_the_check_that_names_its_mistake(
    lesson_id, program, not_solving_folder
):
    result = graded(lesson_id, not_solving_folder)[f"wrong/{program}"]
    lesson_checks = {c.name for c in load_lesson(lesson_dir(lesson_id)).checks}
    for name in named_losses(lesson_dir(lesson_id) / "wrong" / program):
        assert name in lesson_checks, f"{program} names {name!r}, not a check of {lesson_id}"
        lost = [
            v.name for v in result.variants for c in v.checks if c.name == name and not (c.passed or c.gated)
        ]
        assert lost, f"{program} should lose points on {name!r} in some variant"
    assert result.score < result.max_score
