"""A program spells out a hidden world in what it chooses to do: no report of `ev3sim2d grade` passes it on.

The lesson has two hidden variants whose worlds differ only in how far the wall ahead is.  Each program
measures that distance with its ultrasonic sensor and encodes it in something it chooses: the exception
it raises (65 built-in ones to pick from), an exception class of its own, its exit code, the file it
raises from, how much it prints, how long it takes (in virtual and in real time), the signal it crashes
with, how it runs out of memory, how it gets stuck.  The robot never moves, so both hidden variants pass
and fail the same checks with the same status: every report (the terminal's --details, --json, --junit,
--csv, --classroom, --videos) must then say exactly the same of both.  Programs that choose their status
or which check they fail by the distance change only what a hidden variant may show (its status, its
score, which checks passed), in words from a fixed set: `scoring.hidden_texts`.
"""

from __future__ import annotations

import base64
import copy
import csv
import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from ev3sim2d.grading.check import builtin_checks
from ev3sim2d.grading.grader import Grading
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.report import classroom_result
from ev3sim2d.grading.result import HIDDEN_RUN, SubmissionResult
from ev3sim2d.grading.scoring import check_results, hidden_texts
from tests.grading.lesson_maker import LESSON, write_lesson, write_program
from tests.grading.trace_maker import record, room

# The class holds a program that fills the memory (SAME_OUTCOME["memory"]): it is only graded where a
# limit stops it, and ending by it is one of the ways of ending every test here counts on.
pytestmark = pytest.mark.needs_linux("memory_limit")

ROOT = Path(__file__).resolve().parents[2]

# The wall ahead of the start: 37 cm away (near) or 97 cm (far); the goal 20 to 30 cm ahead in both.
NEAR = """\
title: Near room
cell_cm: 10
legend:
  G: {color: green, region: goal}
grid: |
  ########
  #......#
  #......#
  #...GG.#
  #......#
  #......#
  ########
start: {x_cm: 25, y_cm: 35, heading_deg: 0}
"""
FAR = NEAR.replace("Near", "Far").replace("#......#", "#............#").replace("########", "#" * 14)
FAR = FAR.replace("#...GG.#", "#...GG.......#")
HIDDEN = """\
variants:
  - {name: near-room, world: near.yaml, seed: 3}
  - {name: far-room, world: far.yaml, seed: 3}
"""
LIMITS = "limits: {hang_s: 1, cpu_s: 4, memory_mb: 128, wall_s: 40}"

MEASURE = """\
from ev3dev2.sensor.lego import UltrasonicSensor
d = UltrasonicSensor().distance_centimeters
bucket = int(d // 20)
"""
# each keeps the robot still and ends the same way in both hidden worlds, telling the distance otherwise
SAME_OUTCOME = {
    "exception_type": "raise [ZeroDivisionError, KeyError, ValueError, TypeError, IndexError, OSError][bucket]"
    "(f'the wall is {d} cm away')",
    "exception_class": "raise type(f'WallAt{int(d)}cm', (Exception,), {})(d)",
    "exit_code": "import sys\nsys.exit(int(d))",
    "os_exit": "import os\nos._exit(int(d))",
    "file_name": (
        "import importlib.util, os\nname = f'wall_at_{int(d)}.py'\nopen(name, 'w').write('raise RuntimeError()\\n')\n"
        "spec = importlib.util.spec_from_file_location('wall', os.path.abspath(name))\n"
        "spec.loader.exec_module(importlib.util.module_from_spec(spec))"
    ),
    "prints": "import sys\nfor i in range(int(d) * 3):\n    print('the wall is', d, 'cm away')\n"
    "print(d, file=sys.stderr)\nraise RuntimeError('done')",
    "virtual_time": "import time\ntime.sleep(d / 50)\nraise RuntimeError('late')",
    # (compiled code: real time that depends on the distance, and no virtual time, unlike lines of Python)
    "real_time": "sum(range(int(d) * 400000))\nraise RuntimeError('slow')",
    "signal": "import os, signal\nos.kill(os.getpid(), [signal.SIGSEGV, signal.SIGABRT, signal.SIGBUS, signal.SIGILL,"
    " signal.SIGFPE][bucket])",
    "memory": "blocks = []\nwhile True:\n    blocks.append(bytearray(int(d) * 100_000))",
    # a deadlock between the program's own threads, or a real lock that leaves its clock standing still
    "stuck": "import threading, _thread\nlock = threading.Lock() if d < 60 else _thread.allocate_lock()\n"
    "lock.acquire()\nlock.acquire()",
    # runs to the time limit, which names where each thread was: by a name that tells the distance
    "thread_name": "import threading, time\ndef wait():\n    time.sleep(10**6)\n"
    "threading.Thread(target=wait, name=f'wall at {d} cm', daemon=True).start()\nwhile True:\n    time.sleep(1)",
}
# each chooses its status, or which checks pass, by the distance: allowed to differ, in fixed words only
CHOSEN_OUTCOME = {
    "status": "import time\nif d < 60:\n    raise ValueError(d)\nwhile True:\n    time.sleep(1)",
    "checks": "from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent\n"
    "cm = 28 if d < 60 else 10\n"
    "MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(SpeedPercent(40), SpeedPercent(40), cm / 17.59)",
}


def _grade(*args, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=900,
    )


def _lesson(folder: Path) -> Path:
    text = LESSON.format(time_s=3, extra=LIMITS)
    lesson = write_lesson(folder, lesson_text=text, hidden_text=HIDDEN)
    (lesson / "hidden" / "near.yaml").write_text(NEAR)
    (lesson / "hidden" / "far.yaml").write_text(FAR)
    return lesson


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """The class graded once by the real command, with every output; and the lesson."""
    root = tmp_path_factory.mktemp("hidden-reports")
    lesson = _lesson(root / "lesson")
    for name, body in {**SAME_OUTCOME, **CHOSEN_OUTCOME}.items():
        write_program(root / "class", f"{name}.py", MEASURE + body + "\n")
    done = _grade(
        lesson,
        root / "class",
        "--details",
        "--jobs",
        "2",
        "--json",
        root / "r.json",
        "--junit",
        root / "r.xml",
        "--csv",
        root / "r.csv",
        "--videos",
        root / "videos",
        cwd=root,
    )
    assert done.returncode == 1, done.stderr
    return root, load_lesson(lesson), done


def _name(path: str) -> str:
    return Path(path).stem


def _hidden_pairs(document: dict):
    for submission in document["submissions"]:
        variants = {v["name"]: v for v in submission["variants"]}
        yield _name(submission["submission"]), variants["hidden variant 1"], variants["hidden variant 2"]


def _without_name(variant: dict) -> dict:
    variant = copy.deepcopy(variant)
    variant.pop("name")
    return variant


def test_the_programs_measure_two_different_walls(graded):
    root, _, _ = graded
    document = json.loads((root / "r.json").read_text())
    prints = next(s for s in document["submissions"] if _name(s["submission"]) == "prints")
    assert "the wall is" in prints["variants"][0]["output"][0]  # the visible variant shows what it printed
    lesson = load_lesson(root / "lesson")
    near, far = (v for v in lesson.variants if v.hidden)
    assert near.world().grid != far.world().grid


def test_json_says_the_same_of_both_hidden_variants(graded):
    root, lesson, _ = graded
    document = json.loads((root / "r.json").read_text())
    texts = hidden_texts(lesson)
    seen = set()
    for name, first, second in _hidden_pairs(document):
        for variant in (first, second):
            assert variant["sim_time_s"] is None and variant["output"] is None, name
            assert variant["message"] in texts, (name, variant["message"])
            for check in variant["checks"]:
                assert check["message"] in texts and check["t_s"] is None, (name, check["message"])
        if name in SAME_OUTCOME:
            assert _without_name(first) == _without_name(second), name
            seen.add(first["status"])
    assert seen == {"error", "crashed", "memory", "timeout", "graded"}  # every way of ending was tried


def test_the_terminal_details_say_the_same_of_both_hidden_variants(graded):
    _, lesson, done = graded
    texts = hidden_texts(lesson)
    blocks = re.split(r"\n(?=\S)", done.stdout)  # one block per submission, then the table
    for name in SAME_OUTCOME:
        [block] = [b for b in blocks if b.split(":", 1)[0].endswith(f"{name}.py")]
        sections = re.split(r"\n(?=  \S)", block)
        first = next(s for s in sections if s.startswith("  hidden variant 1:"))
        second = next(s for s in sections if s.startswith("  hidden variant 2:"))
        assert first.replace("hidden variant 1", "hidden variant N") == second.replace(
            "hidden variant 2", "hidden variant N"
        ), name
    for line in done.stdout.splitlines():
        found = re.match(r"  hidden variant \d: [\d.]+/[\d.]+, (passed|failed — (.*))$", line)
        if found and found.group(2):
            assert found.group(2) in texts, line
    hidden_check_lines = re.findall(r"  hidden variant \d:.*\n((?:    .*\n)+)", done.stdout)
    for lines in hidden_check_lines:
        for line in lines.splitlines():
            assert re.match(r"    (PASS|FAIL|----) \w+ \([^)]*\): ", line), line
            assert line.split("): ", 1)[1] in texts, line


def test_junit_says_the_same_of_both_hidden_variants_and_holds_no_wall_clock_time(graded):
    root, lesson, _ = graded
    tree = ET.parse(root / "r.xml").getroot()
    document = json.loads((root / "r.json").read_text())
    for suite in tree:
        cases = {1: [], 2: []}
        for case in suite.findall("testcase"):
            found = re.search(r"\.hidden variant (\d)$", case.get("classname"))
            if found:
                case.set("classname", "hidden")
                cases[int(found.group(1))].append(ET.tostring(case, encoding="unicode"))
        if _name(suite.get("name")) in SAME_OUTCOME:
            assert cases[1] == cases[2], suite.get("name")
    simulated = sum(v["sim_time_s"] or 0 for s in document["submissions"] for v in s["variants"])
    assert float(tree.get("time")) == pytest.approx(simulated, abs=0.01)  # simulated, never wall-clock


def test_csv_and_classroom_say_the_same_of_both_hidden_variants(graded):
    root, lesson, _ = graded
    rows = list(csv.DictReader((root / "r.csv").open(encoding="utf-8-sig")))
    document = json.loads((root / "r.json").read_text())
    for row, submission in zip(rows, document["submissions"], strict=True):
        name = _name(submission["submission"])
        if name in SAME_OUTCOME:
            assert row["hidden variant 1"] == row["hidden variant 2"], name
        result = SubmissionResult.from_dict(submission)
        tests = classroom_result(Grading(lesson, [result]))["tests"]
        hidden = {1: [], 2: []}
        for test in tests:
            found = re.match(r"hidden variant (\d): (.*)", test["name"])
            if found:
                hidden[int(found.group(1))].append({**test, "name": found.group(2)})
                assert test["message"] in hidden_texts(lesson), test["message"]
        if name in SAME_OUTCOME:
            assert hidden[1] == hidden[2], name


def test_classroom_from_the_command_says_no_more(graded, tmp_path):
    root, lesson, _ = graded
    output = tmp_path / "github_output"
    _grade(
        root / "lesson", root / "class" / "exception_type.py", "--classroom", output, "--quiet", cwd=tmp_path
    )
    result = json.loads(base64.b64decode(output.read_text().strip().removeprefix("result=")))
    hidden = [t for t in result["tests"] if t["name"].startswith("hidden variant")]
    assert len(hidden) == 6 and all(t["message"] in hidden_texts(lesson) for t in hidden)
    assert [t["message"] for t in hidden[:3]] == [t["message"] for t in hidden[3:]]


def test_videos_are_kept_for_visible_variants_only(graded):
    root, _, _ = graded
    kept = sorted(str(p.relative_to(root / "videos")) for p in (root / "videos").rglob("*") if p.is_file())
    assert kept and all(Path(p).stem == "room" for p in kept), kept


def test_the_words_a_hidden_variant_can_hold_are_a_fixed_set(graded):
    _, lesson, _ = graded
    run_words = set(HIDDEN_RUN.values())
    assert run_words == {
        "the program finished",
        "the program ran until the time limit",
        "the program stopped with an error",
        "the program got stuck, so it was stopped",
        "the program ran too long, so it was stopped",
        "the program ran out of memory",
        "the program wrote too much to the console, so it was stopped",
        "the run crashed",
        "the program could not be started",
    }
    not_judged = {
        "not judged: " + words
        for words in (
            "the program ran too long, so it was stopped",
            "the program ran out of memory",
            "the program wrote too much to the console, so it was stopped",
            "the run crashed",
            "the program could not be started",
        )
    }
    assert hidden_texts(lesson) == run_words | not_judged | {
        "the robot reached the goal",
        "the robot never reached the goal",
        "the robot stopped in the goal",
        "the robot did not stop in the goal",
        "the program did not end by itself without an error",
        "counts only once the robot reaches the goal (reach did not pass)",
    }


def test_a_checks_words_in_a_hidden_variant_tell_pass_or_fail_only():
    """Every built-in check kind, judged on runs that fail (and pass) in different ways: one sentence each."""
    world = room()
    still = [(30, 30, 0)] * 20
    near_wall = [(30, 30, 0)] + [(78, 30, 0)] * 19
    runs = [
        record(
            world, still, status="error", error={"type": "ZeroDivisionError", "message": "12 cm", "line": 3}
        ),
        record(world, still, status="error", error={"type": "KeyError", "message": "40 cm", "line": 9}),
        record(world, still, status="hung"),
        record(world, near_wall, status="time_limit", end_driving=True),
        record(world, still, status="finished"),
    ]
    params = {"wall_distance": {"min_cm": 30, "max_cm": 31}, "end_heading": {"heading_deg": 0}}
    for kind, cls in builtin_checks().items():
        try:
            check = cls.build(**params.get(kind, {}))
        except TypeError:  # a kind whose required parameters name the world's places: not judged here
            continue
        words = {True: set(), False: set()}
        for run in runs:
            try:
                outcome = check.evaluate(run)
            except Exception:  # noqa: BLE001 - a kind this made-up run cannot feed
                continue
            [result] = check_results([check], [outcome], hidden=True)
            words[result.passed].add(result.message)
        assert all(len(found) <= 1 for found in words.values()), (kind, words)
