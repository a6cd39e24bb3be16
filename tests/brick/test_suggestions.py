"""Python's own "Did you mean" reaches the student, on every Python a brick may run on.

At a terminal, Python (3.10 and later for a NameError or an AttributeError, 3.12 and later for a
`from ... import` too) adds `Did you mean: 'LargeMotor'?` to a misspelt name's error.  A brick formats
the program's error with the traceback module, which leaves it out (all of it before 3.12, a
NameError's in 3.12 and later), so the brick adds it as CPython's Lib/traceback.py computes it
(`_compute_suggestion_error`, `_levenshtein_distance`).  A port the EV3 does not have gets a hint
naming the EV3's ports and the robot's devices.
"""

import pytest

from ev3sim2d.brick.suggestions import distance, suggestion, with_suggestion


def _error(run, source):
    result = run(source)
    assert result.status == "error", result.reason
    return result.error


@pytest.mark.parametrize(
    ("source", "last_line"),
    [
        (
            "from ev3dev2.motor import LargeMotr\n",
            "ImportError: cannot import name 'LargeMotr' from 'ev3dev2.motor'",
        ),
        (
            "from ev3dev2.motor import *\nm = LargeMotr(OUTPUT_B)\n",
            "NameError: name 'LargeMotr' is not defined. Did you mean: 'LargeMotor'?",
        ),
        (
            "from ev3dev2.motor import LargeMotor, OUTPUT_B\nLargeMotor(OUTPUT_B).on_for_rotation(50, 1)\n",
            "AttributeError: 'LargeMotor' object has no attribute 'on_for_rotation'. "
            "Did you mean: 'on_for_rotations'?",
        ),
        (
            "from ev3dev2.sensor.lego import ColorSensor\nprint(ColorSensor().reflected_light_intensty)\n",
            "AttributeError: 'ColorSensor' object has no attribute 'reflected_light_intensty'. "
            "Did you mean: 'reflected_light_intensity'?",
        ),
        (
            "class Robot:\n    def __init__(self):\n        self.speed = 30\n"
            "    def go(self):\n        return speed\nRobot().go()\n",
            "NameError: name 'speed' is not defined. Did you mean: 'self.speed'?",
        ),
    ],
)
def test_a_misspelt_name_gets_pythons_suggestion(run, source, last_line):
    error = _error(run, source)
    shown = error["traceback"].rstrip().splitlines()[-1]
    assert shown.startswith(last_line), shown
    assert "Did you mean" in shown and shown.count("Did you mean") == 1
    assert "Did you mean" in error["message"]


def test_the_from_import_suggestion_names_the_class(run):
    error = _error(run, "from ev3dev2.motor import LargeMotr\n")
    assert error["message"].endswith(". Did you mean: 'LargeMotor'?")


def test_a_name_nothing_is_near_gets_no_suggestion(run):
    error = _error(run, "from ev3dev2.motor import *\nm = Zebra(OUTPUT_B)\n")
    assert error["message"] == "name 'Zebra' is not defined"


@pytest.mark.parametrize(
    "source",
    [
        "from ev3dev2.sensor import INPUT_5\n",
        "from ev3dev2.motor import *\nLargeMotor(OUTPUT_E)\n",
        "import ev3dev2.sensor as s\ns.INPUT_0\n",
    ],
)
def test_a_port_the_ev3_does_not_have_gets_a_hint_naming_its_ports(run, source):
    error = _error(run, source)
    assert error["hint"].startswith(
        "an EV3 has four input ports for sensors, INPUT_1 to INPUT_4, and four output ports for motors, "
        "OUTPUT_A to OUTPUT_D; this robot has: "
    )
    assert "in1 touch sensor" in error["hint"] or "outB large motor" in error["hint"]


def test_a_real_port_misspelt_otherwise_gets_no_port_hint(run):
    error = _error(run, "from ev3dev2.sensor import INPUT_1, Colour\n")
    assert error["hint"] is None


@pytest.mark.parametrize(
    ("a", "b", "expected"),
    [
        ("LargeMotr", "LargeMotor", 2),  # one letter left out
        ("largemotor", "LargeMotor", 2),  # two letters' case: 1 each
        ("on_for_rotation", "on_for_rotations", 2),
        ("INPUT_5", "INPUT_1", 2),
        ("abc", "abc", 0),
        ("kitten", "sitting", 6),
    ],
)
def test_the_distance_counts_as_cpython_does(a, b, expected):
    assert distance(a, b, 100) == expected


def test_the_distance_stops_early_past_its_limit():
    assert distance("a" * 10, "b" * 10, 3) == 4


def test_a_hint_already_there_is_not_added_twice():
    try:
        ev3dev2_like = type("M", (), {"LargeMotor": 1})()
        ev3dev2_like.LargeMotr  # noqa: B018
    except AttributeError as exc:
        assert suggestion(exc) == "LargeMotor"
        line = "AttributeError: x. Did you mean: 'LargeMotor'?\n"
        assert with_suggestion(line, exc) == line
