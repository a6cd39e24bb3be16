"""Reading lesson.yaml: what a teacher writes, and the line-numbered errors for their mistakes."""

import pytest

from ev3sim2d.grading.lesson import find_lesson, list_shipped_lessons, load_lesson
from ev3sim2d.world.source_error import WorldFileError

from .lesson_maker import LESSON, write_lesson


def lesson_with(tmp_path, text):
    return write_lesson(tmp_path / "lesson", lesson_text=text)


def error_of(tmp_path, text) -> WorldFileError:
    with pytest.raises(WorldFileError) as caught:
        load_lesson(lesson_with(tmp_path, text))
    return caught.value


def test_a_lesson_reads_its_variants_and_checks(tmp_path):
    lesson = load_lesson(write_lesson(tmp_path / "lesson"))
    assert lesson.title == "Reach the goal" and lesson.time_s == 5
    assert [v.name for v in lesson.variants] == ["room", "hidden-room"]
    assert [v.name for v in lesson.visible_variants()] == ["room"]
    assert lesson.variants[1].seed == 3
    assert [c.name for c in lesson.checks] == ["reach", "stop", "finished"]
    assert lesson.variant_points == 5 and lesson.max_score == 10


def test_shipped_lessons_are_found_by_id():
    assert "line-follow" in list_shipped_lessons()
    assert find_lesson("line-follow").name == "line-follow"


def test_an_unknown_lesson_lists_the_shipped_ones():
    with pytest.raises(WorldFileError, match="shipped lessons: .*line-follow"):
        find_lesson("no-such-lesson")


def test_an_unknown_check_kind_names_its_line_and_suggests(tmp_path):
    err = error_of(
        tmp_path, LESSON.format(time_s=5, extra="").replace("kind: reach_region", "kind: reach_regoin")
    )
    assert err.line == 13 and "unknown check kind 'reach_regoin'; did you mean 'reach_region'?" in err.message


def test_a_region_the_world_lacks_is_an_error_at_the_check(tmp_path):
    err = error_of(
        tmp_path,
        LESSON.format(time_s=5, extra="").replace("region: goal, points: 3", "region: gaol, points: 3"),
    )
    assert err.line == 13
    assert "has no region 'gaol'; its regions: goal" in err.message


def test_a_missing_parameter_says_what_to_add(tmp_path):
    err = error_of(
        tmp_path,
        LESSON.format(time_s=5, extra="").replace("kind: reach_region, region: goal", "kind: reach_region"),
    )
    assert "needs 'region'" in err.message and "region: goal" in err.message


def test_a_wrong_parameter_type(tmp_path):
    text = LESSON.format(time_s=5, extra="") + "  - {kind: lap, within_s: soon}\n"
    err = error_of(tmp_path, text)
    assert err.line == 16 and "'within_s' must be a number" in err.message


def test_an_unknown_key_and_a_missing_world(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="titel: x"))
    assert err.line == 4 and "unknown key 'titel'" in err.message and "did you mean 'title'?" in err.message
    err = error_of(
        tmp_path,
        LESSON.format(time_s=5, extra="").replace(
            "world: room.yaml\n  - name: hidden", "world: nowhere.yaml\n  - name: hidden"
        ),
    )
    assert err.line == 7 and "no world file 'nowhere.yaml'" in err.message


def test_duplicate_names_and_all_hidden(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="").replace("name: finished", "name: reach"))
    assert "two checks are named 'reach'" in err.message
    err = error_of(
        tmp_path,
        LESSON.format(time_s=5, extra="").replace(
            "world: room.yaml\n  - name", "world: room.yaml\n    hidden: true\n  - name"
        ),
    )
    assert "every variant is hidden" in err.message


def test_a_start_inside_a_wall_is_refused_at_the_variant(tmp_path):
    text = LESSON.format(time_s=5, extra="").replace(
        "    seed: 3\n", "    seed: 3\n    start: {x_cm: 15, y_cm: 35}\n"
    )
    err = error_of(tmp_path, text)
    assert err.line == 12 and "variant 'hidden-room'" in err.message and "inside a wall" in err.message


def test_variants_change_the_start_robot_and_noise(tmp_path):
    text = LESSON.format(time_s=5, extra="").replace(
        "    seed: 3\n",
        "    seed: 3\n    start: {x_cm: 45, y_cm: 45, heading_deg: 90}\n    noise: {color: 2.5}\n    time_s: 9\n",
    )
    lesson = load_lesson(lesson_with(tmp_path, text))
    hidden = lesson.variant("hidden-room")
    world = hidden.world()
    assert (world.start.x_cm, world.start.y_cm, world.start.heading_deg) == (45, 45, 90)
    assert next(s for s in world.robot.sensors if s.kind == "color").noise == 2.5
    assert hidden.time_s == 9
    assert lesson.variant("room").world().start.x_cm == 25


def test_a_lessons_own_check_kind(tmp_path):
    folder = write_lesson(
        tmp_path / "lesson",
        lesson_text=LESSON.format(time_s=5, extra="") + "  - {kind: always, points: 2, says: hello}\n",
    )
    (folder / "check_always.py").write_text(
        "from ev3sim2d.grading.check import Check, Outcome, Param\n\n"
        "class Always(Check):\n"
        "    KIND = 'always'\n"
        "    SUMMARY = 'always passes'\n"
        "    PARAMS = (Param('says', 'text', 'what to say'),)\n\n"
        "    def evaluate(self, run):\n"
        "        return Outcome(True, self.says)\n"
    )
    lesson = load_lesson(folder)
    check = lesson.checks[-1]
    assert check.KIND == "always" and check.points == 2 and check.says == "hello"


def test_the_digest_changes_with_the_lesson(tmp_path):
    folder = write_lesson(tmp_path / "lesson")
    first = load_lesson(folder).digest()
    assert load_lesson(folder).digest() == first
    (folder / "lesson.yaml").write_text(LESSON.format(time_s=6, extra=""))
    assert load_lesson(folder).digest() != first
