"""Lessons with other robots besides the student's (`others:`): each driven by a program of the lesson's own
that the student's program cannot read, each check graded on the robot it names, reported per robot."""

import json
from pathlib import Path

import pytest

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.report import details, write_json
from ev3sim2d.grading.submission import find_submissions
from ev3sim2d.world.source_error import WorldFileError

from .lesson_maker import GOOD, write_program

ROOM = """\
# A room with a goal 30 cm ahead of start 1, and a second start far to the right.
title: Test room for two
cell_cm: 10
legend:
  G: {color: green, region: goal}
grid: |
  ################
  #..............#
  #..............#
  #...GG.........#
  #..............#
  #..............#
  ################
start:
  - {x_cm: 25, y_cm: 35, heading_deg: 0}
  - {x_cm: 125, y_cm: 35, heading_deg: 180}
"""

LESSON = """\
title: Reach the goal, with company
goal: Drive 30 cm ahead into the green goal and stop there, while another robot drives towards you.
time_s: 5
{extra}
variants:
  - name: room
    world: room.yaml
checks:
  - {{name: reach, kind: reach_region, region: goal, goal: true, points: 3}}
  - {{name: no-bump, kind: robot_contacts, goal: false, points: 1}}
  - {{name: pacer-moved, kind: end_near, robot: pacer, place: {{at: [105, 35]}}, within_cm: 5, points: 1}}
"""
OTHERS = "others: [{name: pacer, program: pacer.py, start: 2}]"
# the lesson's own program: drives 20 cm towards the student's robot and stops, never reaching the goal
PACER = """\
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(SpeedPercent(30), SpeedPercent(30), 20 / 17.59)
"""
# reaches the goal only if it can read the file it is given: a student's program after the pacer's source
READS_THEN_DRIVES = """\
import sys
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
try:
    with open({path!r}) as f:
        f.read()
except OSError as err:
    print("cannot read:", type(err).__name__)
    sys.exit(0)
MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(SpeedPercent(40), SpeedPercent(40), 28 / 17.59)
"""


def write_lesson(folder, extra=OTHERS, lesson_text=None):
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "room.yaml").write_text(ROOM)
    (folder / "pacer.py").write_text(PACER)
    (folder / "lesson.yaml").write_text(lesson_text or LESSON.format(extra=extra))
    return folder


def error_of(tmp_path, extra, lesson_text=None) -> WorldFileError:
    with pytest.raises(WorldFileError) as caught:
        load_lesson(write_lesson(tmp_path / "lesson", extra, lesson_text))
    return caught.value


def test_a_lesson_names_its_other_robots_and_where_each_starts(tmp_path):
    lesson = load_lesson(write_lesson(tmp_path / "lesson"))
    variant = lesson.variants[0]
    assert lesson.several_robots
    assert variant.robot_names == ["student", "pacer"]
    assert variant.others[0].program == (tmp_path / "lesson" / "pacer.py").resolve()
    entry = tmp_path / "alice.py"
    assert variant.programs(entry) == [entry, variant.others[0].program]
    assert variant.readable(tmp_path) == [[tmp_path], [variant.others[0].program]]
    assert [c.robot for c in lesson.checks] == [None, None, "pacer"]


def test_the_student_may_take_another_start(tmp_path):
    extra = "student_start: 2\nothers: [{name: pacer, program: pacer.py, start: 1}]"
    variant = load_lesson(write_lesson(tmp_path / "lesson", extra)).variants[0]
    assert variant.robot_names == ["pacer", "student"]
    assert variant.student_index == 1 and variant.robot_index("pacer") == 0


@pytest.mark.parametrize(
    "extra, words",
    [
        ("others: [{name: pacer, program: pacer.py, start: 1}]", "other than the student's (1)"),
        ("others: [{name: pacer, program: pacer.py, start: 3}]", "take starts 1 to 2"),
        ("others: [{name: pacer, program: nowhere.py, start: 2}]", "no program 'nowhere.py'"),
        ("others: [{name: student, program: pacer.py, start: 2}]", "other than 'student'"),
        ("", "has only student"),  # a check names the pacer, and there is none
    ],
)
def test_mistakes_in_other_robots_are_reported_with_their_line(tmp_path, extra, words):
    err = error_of(tmp_path, extra)
    assert words in str(err) and "lesson.yaml:" in str(err)


def test_a_check_of_another_robot_cannot_be_the_goal(tmp_path):
    text = LESSON.format(extra=OTHERS).replace("within_cm: 5, points: 1", "within_cm: 5, goal: true")
    assert "cannot be a goal" in str(error_of(tmp_path, OTHERS, text))


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    root = tmp_path_factory.mktemp("two-robots")
    lesson = load_lesson(write_lesson(root / "lesson"))
    programs = root / "class"
    pacer = lesson.variants[0].others[0].program
    write_program(programs, "a_good.py", GOOD)
    write_program(programs, "b_reads_pacer.py", READS_THEN_DRIVES.format(path=str(pacer)))
    own = programs / "c_reads_itself.py"  # the same program, given a file it may read: its own, by the
    write_program(programs, own.name, READS_THEN_DRIVES.format(path=own.name))  # relative path a brick knows
    grading = grade(lesson, find_submissions([programs]), jobs=2)
    return {Path(r.submission).name: r for r in grading.results}, grading, root


@pytest.mark.needs_linux("linux_kernel")  # Landlock keeps the lesson's programs from the student's
def test_the_students_program_cannot_read_the_lesson_programs(graded):
    results, _, _ = graded
    assert results["c_reads_itself.py"].full_marks  # reading works, and reaching the goal scores
    cheat = results["b_reads_pacer.py"]
    reach = next(c for c in cheat.variants[0].checks if c.name == "reach")
    assert not reach.passed and cheat.score == 0


def test_each_check_is_graded_and_reported_on_its_robot(graded, tmp_path):
    results, grading, _ = graded
    good = results["a_good.py"]
    assert good.full_marks, details(good)
    checks = {c.name: c for c in good.variants[0].checks}
    assert (checks["reach"].robot, checks["no-bump"].robot, checks["pacer-moved"].robot) == (
        "student",
        "student",
        "pacer",
    )
    assert "ended" in checks["pacer-moved"].message  # the pacer's end, not the student's
    assert "(1/1, robot: pacer)" in details(good)
    write_json(tmp_path / "results.json", grading)
    data = json.loads((tmp_path / "results.json").read_text())
    robots = [c["robot"] for c in data["submissions"][0]["variants"][0]["checks"]]
    assert robots == ["student", "student", "pacer"]
