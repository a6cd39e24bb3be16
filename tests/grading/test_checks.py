"""Each built-in check kind, on made-up traces in small worlds: what passes, what fails, and what it says."""

import pytest

from ev3sim2d.grading.check import builtin_checks
from ev3sim2d.grading.place import Place

from .trace_maker import line, record, room

CHECKS = builtin_checks()
GOAL = "regions:\n  goal:\n    rect_cm: [70, 50, 90, 70]\n  danger:\n    rect_cm: [40, 10, 50, 70]\n"


def check(kind, **values):
    return CHECKS[kind].build(**values)


def test_reach_region_says_when_the_robot_got_there():
    world = room(GOAL)
    run = record(world, line((30, 30), (80, 60), 100))
    outcome = check("reach_region", region="goal").evaluate(run)
    assert outcome.passed and "reached the goal at" in outcome.message
    assert 0.6 < outcome.t_s < 0.9


def test_reach_region_too_late_or_never():
    world = room(GOAL)
    late = check("reach_region", region="goal", within_s=0.5).evaluate(
        record(world, line((30, 30), (80, 60), 100))
    )
    assert not late.passed and "later than 0.5 s" in late.message
    never = check("reach_region", region="goal").evaluate(record(world, line((30, 30), (50, 30), 50)))
    assert not never.passed and "never reached the goal" in never.message and "cm away" in never.message


def test_reach_region_with_a_label_and_the_colour_sensor():
    world = room(GOAL)
    poses = line((30, 60), (66, 60), 36)  # the centre stops 4 cm short; the colour sensor is 7 cm ahead
    outcome = check("reach_region", region="goal", label="the green goal", point="color-sensor").evaluate(
        record(world, poses)
    )
    assert outcome.passed and outcome.message.startswith("the colour sensor reached the green goal")
    assert not check("reach_region", region="goal").evaluate(record(world, poses)).passed


def test_stop_in_region_needs_the_motors_stopped():
    world = room(GOAL)
    poses = line((30, 30), (80, 60), 100)
    assert check("stop_in_region", region="goal").evaluate(record(world, poses)).passed
    driving = check("stop_in_region", region="goal").evaluate(record(world, poses, end_driving=True))
    assert not driving.passed and "still driving" in driving.message


def test_stop_in_region_names_where_the_robot_stopped_instead():
    world = room(GOAL)
    outcome = check("stop_in_region", region="goal").evaluate(record(world, line((30, 30), (45, 30), 30)))
    assert not outcome.passed
    assert "in the danger region" in outcome.message and "cm from the goal" in outcome.message


def test_avoid_region():
    world = room(GOAL)
    crossed = check("avoid_region", region="danger").evaluate(record(world, line((30, 30), (60, 30), 30)))
    assert not crossed.passed and "went into the danger at 0.1 s" in crossed.message
    assert check("avoid_region", region="danger").evaluate(record(world, line((30, 30), (35, 30), 5))).passed


def test_end_near_the_start_or_a_point():
    world = room()
    there_and_back = line((30, 30), (60, 30), 30) + line((60, 30), (32, 30), 28)[1:]
    assert check("end_near", within_cm=5).evaluate(record(world, there_and_back)).passed
    far = check("end_near", within_cm=1).evaluate(record(world, there_and_back))
    assert not far.passed and "ended 2.0 cm from the start (at most 1 cm passes)" in far.message
    point = check("end_near", place=Place(at=(60, 30)), within_cm=1).evaluate(
        record(world, line((30, 30), (60, 30), 30))
    )
    assert point.passed


def test_end_heading_relative_to_the_start():
    world = room()
    turned = [(30, 30, h) for h in range(0, -91, -1)]  # a quarter turn to the right
    assert check("end_heading", from_start_deg=-90, within_deg=2).evaluate(record(world, turned)).passed
    wrong = check("end_heading", within_deg=5).evaluate(record(world, turned))
    assert not wrong.passed and "90.0° to the right of its start heading" in wrong.message
    assert check("end_heading", heading_deg=270, within_deg=1).evaluate(record(world, turned)).passed


def test_wall_contacts_counts_each_contact_with_its_time():
    world = room()
    poses = [(30, 30, 0)] * 101
    touching = [False] * 101
    for i in list(range(20, 30)) + list(range(60, 70)):
        touching[i] = True
    outcome = check("wall_contacts").evaluate(record(world, poses, touching=touching))
    assert not outcome.passed and "touched a wall 2 times, first at 0.2 s" in outcome.message
    assert check("wall_contacts", max=2).evaluate(record(world, poses, touching=touching)).passed
    too_long = check("wall_contacts", max=2, max_touch_s=0.1).evaluate(
        record(world, poses, touching=touching)
    )
    assert not too_long.passed and "0.2 s in all" in too_long.message
    assert check("wall_contacts").evaluate(record(world, poses)).message == "never touched a wall"


def test_checkpoints_in_order():
    world = room(GOAL)
    places = (Place(from_start=(20, 0), radius_cm=3, label="A"), Place(region="goal"))
    path = line((30, 30), (50, 30), 20) + line((50, 30), (80, 60), 30)[1:]
    assert check("checkpoints", places=places).evaluate(record(world, path)).passed
    backwards = check("checkpoints", places=tuple(reversed(places))).evaluate(record(world, path))
    assert (
        not backwards.passed
        and "passed checkpoint 1 at" in backwards.message
        and "never reached checkpoint 2, A" in backwards.message
    )
    unordered = check("checkpoints", places=tuple(reversed(places)), in_order=False).evaluate(
        record(world, path)
    )
    assert unordered.passed


def test_wall_distance_from_the_ultrasonic_sensor():
    world = room()  # the wall on the right starts at x = 90; the sensor is 8 cm ahead of the centre
    near = check("wall_distance", min_cm=8, max_cm=12).evaluate(record(world, line((30, 30), (72, 30), 42)))
    assert near.passed and "10.0 cm from the wall" in near.message
    far = check("wall_distance", min_cm=8, max_cm=12).evaluate(record(world, line((30, 30), (50, 30), 20)))
    assert not far.passed and "too far from the wall" in far.message and "32.0 cm" in far.message
    front = check("wall_distance", min_cm=0, max_cm=1, **{"from": "front"}).evaluate(
        record(world, line((30, 30), (80.5, 30), 50))
    )
    assert front.passed


def test_lap_needs_going_away_and_coming_back():
    world = room()
    out_and_back = (
        line((20, 20), (80, 20), 60) + line((80, 20), (80, 60), 40)[1:] + line((80, 60), (20, 20), 70)[1:]
    )
    outcome = check("lap", min_away_cm=50, radius_cm=5).evaluate(record(world, out_and_back))
    assert outcome.passed and "completed a lap at 1.7 s" in outcome.message
    short = check("lap", min_away_cm=50, min_path_cm=500).evaluate(record(world, out_and_back))
    assert not short.passed and "did not come back" in short.message
    assert "never got 50 cm" in check("lap").evaluate(record(world, line((20, 20), (40, 20), 20))).message


LINE_ROOM = (
    ["#" + "." * 8 + "#"] * 2 + ["#" + "k" * 8 + "#"] + ["#" + "." * 8 + "#"] * 3
)  # a black row at y 40..50


def test_on_line_follows_the_colour_sensor():
    world = room(inner=LINE_ROOM)
    on = line((10, 45), (70, 45), 60)  # the colour sensor, 7 cm ahead, stays over the line
    assert check("on_line").evaluate(record(world, on)).passed
    off = line((10, 45), (40, 45), 30) + line((40, 45), (40, 15), 300)[1:]
    lost = check("on_line").evaluate(record(world, off))
    assert not lost.passed and "left the line at 0.3 s and did not find it again" in lost.message


def test_on_line_stretches_off_the_line_and_gaps():
    world = room(inner=LINE_ROOM, extra="regions:\n  gap:\n    rect_cm: [30, 0, 60, 80]\n")
    path = (
        line((10, 45), (30, 45), 20)
        + line((30, 45), (50, 25), 20)[1:]
        + line((50, 25), (60, 45), 20)[1:]
        + line((60, 45), (80, 45), 10)[1:]
    )
    outcome = check("on_line", max_off_s=0.1, min_fraction=0.1).evaluate(record(world, path))
    assert (
        not outcome.passed
        and "was off the line from" in outcome.message
        and "at most 0.1 s passes" in outcome.message
    )
    assert check("on_line", max_off_s=0.1, min_fraction=0.1, gaps="gap").evaluate(record(world, path)).passed


def test_finished_explains_how_the_program_ended():
    world = room()
    poses = line((30, 30), (40, 30), 10)
    assert check("finished").evaluate(record(world, poses)).passed
    error = {"type": "ZeroDivisionError", "message": "division by zero", "line": 7}
    failed = check("finished").evaluate(record(world, poses, status="error", error=error))
    assert (
        failed.message
        == "the program stopped with an error at 0.1 s: ZeroDivisionError: division by zero (line 7)"
    )
    assert (
        "still running at the time limit"
        in check("finished").evaluate(record(world, poses, status="time_limit")).message
    )
    assert "got stuck" in check("finished").evaluate(record(world, poses, status="hung")).message
    assert "later than 0.05 s" in check("finished", within_s=0.05).evaluate(record(world, poses)).message


def test_stopped():
    world = room()
    poses = line((30, 30), (40, 30), 10) + [(40, 30, 0)] * 50
    outcome = check("stopped").evaluate(record(world, poses))
    assert outcome.passed and outcome.message == "the robot stopped at 0.1 s"
    assert not check("stopped").evaluate(record(world, poses, end_driving=True)).passed
    assert not check("stopped", by_s=0.05).evaluate(record(world, poses)).passed


@pytest.mark.parametrize("kind", sorted(CHECKS))
def test_every_kind_is_documented(kind):
    cls = CHECKS[kind]
    assert cls.SUMMARY and cls.__doc__
    docs = (__import__("pathlib").Path(__file__).resolve().parents[2] / "docs" / "lessons.md").read_text()
    assert f"`{kind}`" in docs
    for param in cls.PARAMS:
        assert f"`{param.name}`" in docs, f"{kind}.{param.name} is not in docs/lessons.md"


def test_robot_contacts_counts_the_times_the_robot_touches_another():
    world = room()
    poses = line((30, 30), (60, 30), 30)
    bumps = [False] * 10 + [True] * 5 + [False] * 5 + [True] * 3 + [False] * 8
    outcome = check("robot_contacts").evaluate(record(world, poses, touching_robot=bumps))
    assert not outcome.passed
    assert outcome.message == "touched another robot 2 times, first at 0.1 s (no contact passes)"
    assert check("robot_contacts", max=2).evaluate(record(world, poses, touching_robot=bumps)).passed
    walls = check("robot_contacts").evaluate(record(world, poses, touching=bumps))
    assert walls.passed and walls.message == "never touched another robot"  # a wall is not a robot
