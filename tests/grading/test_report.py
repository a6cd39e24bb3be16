"""The table, details, JSON, JUnit XML and CSV written from grading results; what they show of hidden variants."""

import csv
import json
import re
import xml.etree.ElementTree as ET

import pytest

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.report import details, table, write_csv, write_json, write_junit
from ev3sim2d.grading.result import SubmissionResult
from ev3sim2d.grading.submission import find_submissions

from .lesson_maker import GOOD, SHORT, write_lesson, write_program

WRONG_WAY = """\
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_rotations(SpeedPercent(-40), SpeedPercent(-40), 10 / 17.59)
"""


@pytest.fixture(scope="module")
def grading(tmp_path_factory):
    root = tmp_path_factory.mktemp("report")
    lesson = load_lesson(write_lesson(root / "lesson"))
    write_program(root / "class", "alice.py", GOOD)
    write_program(root / "class", "bob.py", SHORT)
    return grade(lesson, find_submissions([root / "class", root / "nobody.py"]), jobs=2)


def test_json_holds_score_status_and_every_check(grading, tmp_path):
    write_json(tmp_path / "r.json", grading)
    data = json.loads((tmp_path / "r.json").read_text())
    alice, bob, nobody = data["submissions"]
    assert set(alice) >= {"submission", "score", "max_score", "status", "variants"}
    assert (alice["score"], alice["max_score"], alice["status"]) == (10, 10, "graded")
    reach, stop, finished = bob["variants"][0]["checks"]
    assert set(reach) >= {"name", "passed", "points", "message", "goal", "gated"}
    assert reach["name"] == "reach" and reach["passed"] is False and reach["points"] == 0 and reach["goal"]
    assert "never reached the goal" in reach["message"]
    assert not stop["gated"] and "stopped" in stop["message"]  # failed on its own: says why
    assert finished["gated"] and finished["points"] == 0
    assert finished["message"] == "counts only once the robot reaches the goal (reach did not pass)"
    assert bob["variants"][1]["hidden"] is True
    assert nobody["status"] == "missing"


def test_junit_has_a_test_per_variant_and_check(grading, tmp_path):
    write_junit(tmp_path / "r.xml", grading)
    root = ET.parse(tmp_path / "r.xml").getroot()
    suites = root.findall("testsuite")
    assert len(suites) == 3
    assert suites[0].get("failures") == "0" and suites[0].get("tests") == "6"
    bob_failures = suites[1].findall("testcase/failure")
    assert len(bob_failures) == 4 and "never reached the goal" in bob_failures[0].get("message")
    skipped = suites[1].findall("testcase/skipped")
    assert suites[1].get("skipped") == "2" and len(skipped) == 2
    assert "counts only once the robot reaches the goal" in skipped[0].get("message")
    assert suites[2].find("testcase/error").get("type") == "missing"


def test_csv_has_a_row_per_submission(grading, tmp_path):
    write_csv(tmp_path / "r.csv", grading)
    rows = list(csv.DictReader((tmp_path / "r.csv").open()))
    assert [r["score"] for r in rows] == ["10", "0", "0"]
    assert rows[0]["percent"] == "100" and rows[0]["room"] == "5" and rows[0]["hidden variant 1"] == "5"
    assert "never reached the goal" in rows[1]["first_problem"]


def test_the_table_and_details_read_well(grading):
    text = table(grading)
    assert "2 variants, 1 of them hidden" in text and "hidden variant 1" in text
    assert "10/10" in text and "0/10" in text
    assert "3 submission(s), 1 with full marks" in text
    bob = details(grading.results[1])
    assert "FAIL reach (0/3, goal): the robot never reached the goal" in bob
    assert "---- finished (0/1): counts only once the robot reaches the goal (reach did not pass)" in bob
    assert "  hidden variant 1: 0/5, failed — the robot never reached the goal" in bob


@pytest.fixture(scope="module")
def class_reports(tmp_path_factory):
    """Every report of a class, as text, with programs that fail the hidden variant in several ways."""
    root = tmp_path_factory.mktemp("hidden")
    lesson = load_lesson(write_lesson(root / "lesson"))
    for name, source in {
        "alice.py": GOOD,
        "bob.py": SHORT,
        "carol.py": WRONG_WAY,
        "dave.py": "x = 1 / 0\n",
        "erin.py": "import time\ntime.sleep(1.5)\nraise ValueError('the wall is 12.5 cm away')\n",
        "fred.py": "class WallAt12cm(Exception):\n    pass\n\nraise WallAt12cm()\n",
    }.items():
        write_program(root / "class", name, source)
    grading = grade(lesson, find_submissions([root / "class"]), jobs=2)
    write_json(root / "r.json", grading)
    write_junit(root / "r.xml", grading)
    write_csv(root / "r.csv", grading)
    texts = {name: (root / name).read_text() for name in ("r.json", "r.xml", "r.csv")}
    texts["table"] = table(grading)
    texts["details"] = "\n".join(details(r) for r in grading.results)
    return grading, texts


def test_no_report_names_a_hidden_variant_or_its_world(class_reports):
    grading, texts = class_reports
    for name, text in texts.items():
        assert "hidden-room" not in text, name
    document = json.loads(texts["r.json"])
    assert document["variants"][1] == {"name": "hidden variant 1", "hidden": True}
    assert document["variants"][0]["world"]


def test_a_hidden_variant_shows_its_score_and_what_went_wrong_in_words_only(class_reports):
    grading, texts = class_reports
    assert [r.score for r in grading.results] == [10, 0, 0, 0, 0, 0]  # the hidden variant's score counts
    for result in grading.results:
        hidden = result.variants[1]
        assert hidden.name == "hidden variant 1" and hidden.sim_time_s is None
        for text in [hidden.message, *(c.message for c in hidden.checks)]:
            assert not re.search(r"\d", text.replace("hidden variant 1", "")), text
        assert all(c.t_s is None for c in hidden.checks)
    details_of = texts["details"]
    assert "hidden variant 1: 0/5, failed — the robot never reached the goal" in details_of
    assert "hidden variant 1: 0/5, failed — the program stopped with an error" in details_of
    hidden_lines = [line for line in details_of.splitlines() if line.lstrip().startswith("hidden variant")]
    assert hidden_lines and not any("Error" in line for line in hidden_lines)  # which error: the program's choice
    erin = grading.results[4]
    assert "12.5 cm" in erin.variants[0].message  # a visible variant shows the error in full
    assert erin.variants[1].message == "the program stopped with an error"
    fred = grading.results[5]  # an exception class of its own could be named after what it measured
    assert "WallAt12cm" in fred.variants[0].message
    assert fred.variants[1].message == "the program stopped with an error"


def test_the_first_problem_of_a_hidden_variant_is_a_line_without_numbers(class_reports):
    grading, _ = class_reports
    line = grading.results[2].first_failure()  # carol fails the visible variant first
    assert line.startswith("room: reach: ")
    hidden_only = SubmissionResult("x", "k", [grading.results[0].variants[0], grading.results[2].variants[1]])
    assert hidden_only.first_failure() == "hidden variant 1: failed — the robot never reached the goal"
