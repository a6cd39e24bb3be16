"""The gating rule: secondary checks count only once every goal check of the variant passes; and what a
hidden variant's result keeps (its score, words without numbers)."""

import re

import pytest

from ev3sim2d.grading.check import Check, Outcome, builtin_checks
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.scoring import check_results, score_run

from .lesson_maker import write_lesson
from .trace_maker import line, record

CHECKS = builtin_checks()


def outcomes(*passed):
    return [Outcome(p, f"{'passed' if p else 'failed'} at 1.5 s", 1.5) for p in passed]


def checks(*goals):
    return [CHECKS["finished"].build(name=f"c{i}", points=i + 1, goal=g) for i, g in enumerate(goals)]


def test_secondary_checks_count_once_the_goal_is_met():
    results = check_results(checks(True, False, False), outcomes(True, True, False))
    assert [(r.passed, r.points, r.gated) for r in results] == [
        (True, 1, False),
        (True, 2, False),
        (False, 0, False),
    ]


def test_a_missed_goal_holds_back_the_secondary_checks_that_pass():
    results = check_results(checks(True, False, False), outcomes(False, True, False))
    assert [(r.passed, r.points, r.gated) for r in results] == [
        (False, 0, False),
        (False, 0, True),
        (False, 0, False),
    ]
    assert results[1].message == "counts only once the robot reaches the goal (c0 did not pass)"
    assert results[1].t_s is None
    assert results[2].message == "failed at 1.5 s"  # failed on its own: its own reason


def test_with_several_goals_each_earns_its_points_and_all_must_pass_for_the_rest():
    results = check_results(checks(True, True, False), outcomes(True, False, True))
    assert [r.points for r in results] == [1, 0, 0]
    assert results[2].gated and "(c1 did not pass)" in results[2].message
    both = check_results(checks(True, True, False), outcomes(False, False, True))
    assert "(c0, c1 did not pass)" in both[2].message


def test_goal_checks_are_marked_in_the_results():
    results = check_results(checks(True, False), outcomes(True, True))
    assert [r.goal for r in results] == [True, False]


@pytest.fixture
def lesson(tmp_path):
    return load_lesson(write_lesson(tmp_path / "lesson"))


def run_in(lesson, variant, poses, **options):
    world = lesson.variants[variant].world()
    return record(world, poses, **options)


def test_a_robot_that_stands_still_scores_nothing(lesson):
    for variant in (0, 1):
        scored = score_run(lesson, variant, run_in(lesson, variant, [(25, 35, 0)] * 100))
        assert scored.score == 0
        assert [(c.name, c.gated) for c in scored.checks if c.gated] == [("finished", True)]


def test_a_robot_that_reaches_the_goal_earns_every_check(lesson):
    scored = score_run(lesson, 0, run_in(lesson, 0, line((25, 35), (50, 35), 50)))
    assert scored.score == 5 and scored.passed and not any(c.gated for c in scored.checks)


def test_a_hidden_variant_keeps_its_score_and_words_but_no_numbers(lesson):
    short = line((25, 35), (30, 35), 50)
    visible = score_run(lesson, 0, run_in(lesson, 0, short))
    hidden = score_run(lesson, 1, run_in(lesson, 1, short))
    assert "cm away" in visible.checks[0].message and visible.sim_time_s == 0.5
    assert hidden.name == "hidden variant 1" and hidden.hidden and hidden.sim_time_s is None
    assert hidden.score == visible.score and hidden.message == "the program finished"
    assert hidden.checks[0].message == "the robot never reached the goal"
    for check in hidden.checks:
        assert check.t_s is None and not re.search(r"\d", check.message), check.message
    reached = score_run(lesson, 1, run_in(lesson, 1, line((25, 35), (50, 35), 50)))
    assert [c.message for c in reached.checks] == [
        "the robot reached the goal",
        "the robot stopped in the goal",
        "the program finished",
    ]


def test_a_hidden_run_that_left_no_result_says_why_by_its_status_only(lesson):
    from ev3sim2d.grading.scoring import not_run

    said = "the run ended without a result (exit status 4: the wall is 53 cm away)"
    visible, hidden = not_run(lesson, 0, "crashed", said), not_run(lesson, 1, "crashed", said)
    assert visible.message == said and visible.checks[0].message == f"not judged: {said}"
    assert hidden.message == "the run crashed" and hidden.name == "hidden variant 1"
    assert all("53" not in c.message for c in hidden.checks) and hidden.score == 0


def test_a_check_without_a_brief_message_says_passed_or_its_summary():
    class Custom(Check):
        KIND = "custom"
        SUMMARY = "the robot does something"

    custom = Custom.build()
    assert custom.brief_of(Outcome(True, "did it at 3.0 s")) == "passed"
    assert custom.brief_of(Outcome(False, "not at 3.0 s")) == "did not pass (the robot does something)"
    assert custom.brief_of(Outcome(False, "not at 3.0 s", brief="did not")) == "did not"


def test_every_built_in_kind_says_what_it_found_without_numbers():
    from .trace_maker import room

    world = room("regions:\n  goal:\n    rect_cm: [70, 50, 90, 70]\n")
    runs = [record(world, line((30, 30), (80, 60), 100)), record(world, [(30, 30, 0)] * 50, end_driving=True)]
    values = {
        "reach_region": {"region": "goal"},
        "stop_in_region": {"region": "goal"},
        "avoid_region": {"region": "goal"},
        "checkpoints": {"places": (CHECKS["end_near"].build().place,)},
        "wall_distance": {"min_cm": 8, "max_cm": 12},
    }
    for kind, cls in CHECKS.items():
        check = cls.build(**values.get(kind, {}))
        for run in runs:
            if kind == "on_line":
                continue  # needs a line in the world; its messages are tested in test_checks.py
            found = check.evaluate(run)
            assert found.brief, (kind, found.message)
            assert not re.search(r"\d", found.brief), (kind, found.brief)
