"""The table, details, JSON, JUnit XML and CSV written from grading results."""

import csv
import json
import xml.etree.ElementTree as ET

import pytest

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.report import details, table, write_csv, write_json, write_junit
from ev3sim2d.grading.submission import find_submissions

from .lesson_maker import GOOD, SHORT, write_lesson, write_program


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
    check = bob["variants"][0]["checks"][0]
    assert set(check) >= {"name", "passed", "points", "message"}
    assert check["name"] == "reach" and check["passed"] is False and check["points"] == 0
    assert "never reached the goal" in check["message"]
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
    assert suites[2].find("testcase/error").get("type") == "missing"


def test_csv_has_a_row_per_submission(grading, tmp_path):
    write_csv(tmp_path / "r.csv", grading)
    rows = list(csv.DictReader((tmp_path / "r.csv").open()))
    assert [r["score"] for r in rows] == ["10", "2", "0"]
    assert rows[0]["percent"] == "100" and rows[1]["room"] == "1" and rows[1]["hidden-room"] == "1"
    assert "never reached the goal" in rows[1]["first_problem"]


def test_the_table_and_details_read_well(grading):
    text = table(grading)
    assert "hidden-room*" in text and "10/10" in text and "2/10" in text
    assert "3 submission(s), 1 with full marks" in text
    bob = details(grading.results[1])
    assert "FAIL reach (0/3): the robot never reached the goal" in bob
    assert "PASS finished (1/1)" in bob and "hidden-room (hidden)" in bob
