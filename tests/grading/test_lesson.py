"""Reading lesson.yaml and hidden/hidden.yaml: what a teacher writes, and the line-numbered errors for their
mistakes."""

import shutil

import pytest

from ev3sim2d.grading.lesson import find_lesson, list_shipped_lessons, load_lesson
from ev3sim2d.world.source_error import WorldFileError

from .lesson_maker import HIDDEN, LESSON, write_lesson


def lesson_with(tmp_path, text, hidden_text=HIDDEN):
    return write_lesson(tmp_path / "lesson", lesson_text=text, hidden_text=hidden_text)


def error_of(tmp_path, text, hidden_text=HIDDEN) -> WorldFileError:
    with pytest.raises(WorldFileError) as caught:
        load_lesson(lesson_with(tmp_path, text, hidden_text))
    return caught.value


def test_a_lesson_reads_its_variants_and_checks(tmp_path):
    lesson = load_lesson(write_lesson(tmp_path / "lesson"))
    assert lesson.title == "Reach the goal" and lesson.time_s == 5
    assert [v.name for v in lesson.variants] == ["room", "hidden-room"]
    assert [v.name for v in lesson.visible_variants()] == ["room"]
    assert [v.name for v in lesson.hidden_variants()] == ["hidden-room"]
    assert lesson.variants[1].seed == 3
    assert [v.report_name for v in lesson.variants] == ["room", "hidden variant 1"]
    assert [c.name for c in lesson.checks] == ["reach", "stop", "finished"]
    assert [c.name for c in lesson.goal_checks] == ["reach"]
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
    assert err.line == 9 and "unknown check kind 'reach_regoin'; did you mean 'reach_region'?" in err.message


def test_a_region_the_world_lacks_is_an_error_at_the_check(tmp_path):
    err = error_of(
        tmp_path,
        LESSON.format(time_s=5, extra="").replace("region: goal, goal: true", "region: gaol, goal: true"),
    )
    assert err.line == 9
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
    assert err.line == 12 and "'within_s' must be a number" in err.message


def test_an_unknown_key_and_a_missing_world(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="titel: x"))
    assert err.line == 4 and "unknown key 'titel'" in err.message and "did you mean 'title'?" in err.message
    err = error_of(
        tmp_path, LESSON.format(time_s=5, extra="").replace("world: room.yaml", "world: nowhere.yaml")
    )
    assert err.line == 7 and "no world file 'nowhere.yaml'" in err.message


def test_duplicate_names(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="").replace("name: finished", "name: reach"))
    assert "two checks are named 'reach'" in err.message
    err = error_of(tmp_path, LESSON.format(time_s=5, extra=""), HIDDEN.replace("hidden-room", "room"))
    assert err.path.endswith("hidden.yaml") and err.line == 2
    assert "two variants are named 'room'" in err.message


def test_a_lesson_without_a_goal_check_is_refused_at_its_checks(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="").replace("goal: true, ", ""))
    assert err.path.endswith("lesson.yaml") and (err.line, err.column) == (9, 3)
    assert "no check is the lesson's goal" in err.message and "`goal: true`" in err.message


@pytest.mark.parametrize(
    "check",
    [
        "{kind: finished, goal: true}",
        "{kind: stopped, goal: true}",
        "{kind: wall_contacts, goal: true}",
        "{kind: avoid_region, region: goal, goal: true}",
        "{kind: end_near, goal: true}",
    ],
)
def test_a_check_that_a_robot_standing_still_passes_cannot_be_a_goal(tmp_path, check):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra="") + f"  - {check}\n")
    assert err.line == 12 and "passes for a robot that never moves, so it cannot be a goal" in err.message


def test_ending_near_the_start_can_be_a_goal_once_the_robot_must_travel(tmp_path):
    text = LESSON.format(time_s=5, extra="") + "  - {kind: end_near, goal: true, min_path_cm: 50}\n"
    lesson = load_lesson(lesson_with(tmp_path, text))
    assert [c.name for c in lesson.goal_checks] == ["reach", "end_near"]


def test_a_hidden_variant_in_lesson_yaml_is_refused(tmp_path):
    text = LESSON.format(time_s=5, extra="").replace(
        "    world: room.yaml\n",
        "    world: room.yaml\n  - name: secret\n    world: room.yaml\n    hidden: true\n",
    )
    err = error_of(tmp_path, text)
    assert err.path.endswith("lesson.yaml") and err.line == 10
    assert "hidden variants live apart from lesson.yaml, in hidden/hidden.yaml" in err.message
    err = error_of(tmp_path, LESSON.format(time_s=5, extra=""), HIDDEN + "    hidden: false\n")
    assert err.path.endswith("hidden.yaml") and "a visible variant belongs in lesson.yaml" in err.message


def test_without_a_hidden_folder_only_the_visible_variants_are_graded(tmp_path):
    lesson = load_lesson(write_lesson(tmp_path / "lesson", hidden_text=None))
    assert [v.name for v in lesson.variants] == ["room"] and lesson.hidden_file is None
    assert lesson.max_score == 5


def test_hidden_variants_from_a_teachers_private_copy(tmp_path):
    folder = write_lesson(tmp_path / "lesson", hidden_text=None)
    private = tmp_path / "private"
    (private / "lesson").mkdir(parents=True)
    (private / "lesson" / "hidden.yaml").write_text(HIDDEN.replace("room.yaml", "other.yaml"))
    shutil.copyfile(folder / "room.yaml", private / "lesson" / "other.yaml")  # a world only the teacher has
    for given in (private, private / "lesson", private / "lesson" / "hidden.yaml"):
        lesson = load_lesson(folder, hidden=given)
        assert [v.name for v in lesson.variants] == ["room", "hidden-room"]
        assert lesson.variants[1].world_path == private / "lesson" / "other.yaml"
    with pytest.raises(WorldFileError, match="no hidden.yaml for lesson 'lesson' here"):
        load_lesson(folder, hidden=tmp_path / "nowhere")


def test_a_hidden_world_is_looked_for_in_the_hidden_folder_first(tmp_path):
    folder = write_lesson(tmp_path / "lesson")
    shutil.copyfile(folder / "room.yaml", folder / "hidden" / "room.yaml")
    lesson = load_lesson(folder)
    assert lesson.variants[0].world_path == folder / "room.yaml"
    assert lesson.variants[1].world_path == folder / "hidden" / "room.yaml"


def test_a_start_inside_a_wall_is_refused_at_the_variant(tmp_path):
    err = error_of(tmp_path, LESSON.format(time_s=5, extra=""), HIDDEN + "    start: {x_cm: 15, y_cm: 35}\n")
    assert err.path.endswith("hidden.yaml") and err.line == 5
    assert "variant 'hidden-room'" in err.message and "inside a wall" in err.message


def test_variants_change_the_start_robot_and_noise(tmp_path):
    hidden = (
        HIDDEN + "    start: {x_cm: 45, y_cm: 45, heading_deg: 90}\n    noise: {color: 2.5}\n    time_s: 9\n"
    )
    lesson = load_lesson(lesson_with(tmp_path, LESSON.format(time_s=5, extra=""), hidden))
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
    second = load_lesson(folder).digest()
    assert second != first
    (folder / "hidden" / "hidden.yaml").write_text(HIDDEN.replace("seed: 3", "seed: 4"))
    assert load_lesson(folder).digest() != second
