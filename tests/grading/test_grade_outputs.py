"""`ev3sim2d grade`'s outputs as a teacher, a CI job and GitHub Classroom use them, each from the command
run as a user runs it: JUnit XML with standard attributes only, a CSV Excel opens, Classroom's points,
what each program printed, a syntax error said once, exit codes, and `| head`."""

import base64
import json
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

from ev3sim2d.grading.result import OUTPUT_HEAD, OUTPUT_LINE_CHARS, OUTPUT_TAIL

from .lesson_maker import GOOD, SHORT, write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]

# The attributes the JUnit XSD allows (Jenkins' junit-10.xsd, which CI systems follow: GitLab, Jenkins,
# Azure; testsuite's `package` is only in a <testsuites>' suites of the Ant schema), and which elements
# may hold which.
JUNIT_XSD_ATTRIBUTES = {
    "testsuites": {"name", "tests", "failures", "errors", "skipped", "time", "disabled"},
    "testsuite": {
        "name",
        "tests",
        "failures",
        "errors",
        "skipped",
        "time",
        "timestamp",
        "hostname",
        "id",
        "package",
        "disabled",
    },
    "testcase": {"name", "classname", "time", "assertions", "status"},
    "failure": {"message", "type"},
    "error": {"message", "type"},
    "skipped": {"message"},
    "system-out": set(),
    "system-err": set(),
    "properties": set(),
    "property": {"name", "value"},
}
JUNIT_XSD_CHILDREN = {
    "testsuites": {"testsuite"},
    "testsuite": {"properties", "testcase", "system-out", "system-err"},
    "testcase": {"skipped", "error", "failure", "system-out", "system-err"},
    "properties": {"property"},
}

SYNTAX_ERROR = "x = 1\nif x:\n    print('a' +)\n"
CHATTY = GOOD.replace("tank = ", "for i in range(300):\n    print('line', i, 'x' * {n})\ntank = ")


def grade_cli(*args, cwd=None):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd or ROOT,
        timeout=300,
    )


def test_junit_has_only_the_xsds_attributes_and_the_details_in_system_out(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "alice.py", GOOD)
    write_program(tmp_path / "class", "bob.py", SHORT)
    write_program(tmp_path / "class", "carol.py", SYNTAX_ERROR)
    grade_cli(lesson, tmp_path / "class", "--junit", tmp_path / "r.xml", "--quiet")
    root = ET.parse(tmp_path / "r.xml").getroot()
    assert root.tag == "testsuites"
    for element in root.iter():
        assert element.tag in JUNIT_XSD_ATTRIBUTES, element.tag
        assert set(element.attrib) <= JUNIT_XSD_ATTRIBUTES[element.tag], (element.tag, element.attrib)
        allowed = JUNIT_XSD_CHILDREN.get(element.tag, set())
        assert {child.tag for child in element} <= allowed, element.tag
    suites = {suite.get("name"): suite for suite in root}
    bob = suites[str(tmp_path / "class" / "bob.py")]
    reach = next(c for c in bob.iter("testcase") if c.get("name") == "reach")
    assert reach.find("failure") is not None
    assert reach.find("system-out").text.startswith("0/3 points, a goal check\n")
    assert bob.find("system-out").text.endswith("0/10 points (graded)")
    carol = suites[str(tmp_path / "class" / "carol.py")]
    error = carol.find("testcase/error")
    assert "line 3" in error.get("message") and "^" in error.text


def test_csv_starts_with_a_bom_so_excel_reads_utf8(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "klasse", "jürgen.py", GOOD)
    grade_cli(lesson, tmp_path / "klasse", "--csv", tmp_path / "class.csv", "--quiet")
    data = (tmp_path / "class.csv").read_bytes()
    assert data.startswith(b"\xef\xbb\xbfsubmission,")
    assert "jürgen.py".encode() in data


def test_classroom_result_gives_points_out_of_the_lessons_max(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    past_the_goal = GOOD.replace("28 / 17.59", "50 / 17.59")  # reaches the goal, does not stop in it
    prog = write_program(tmp_path, "past.py", past_the_goal)
    output = tmp_path / "github_output"
    output.write_text("earlier=1\n")  # $GITHUB_OUTPUT holds other steps' outputs: appended to
    done = grade_cli(lesson, prog, "--classroom", output, "--json", tmp_path / "r.json", "--quiet")
    assert done.returncode == 1
    lines = output.read_text().splitlines()
    assert lines[0] == "earlier=1" and lines[1].startswith("result=")
    result = json.loads(base64.b64decode(lines[1].removeprefix("result=")))
    graded = json.loads((tmp_path / "r.json").read_text())["submissions"][0]
    assert result["version"] == 1 and result["status"] == "fail"
    assert result["max_score"] == graded["max_score"] == 10
    # what the reporter adds up (notify-classroom.js): the tests' scores, out of max_score
    assert sum(test["score"] for test in result["tests"]) == graded["score"]
    assert 0 < graded["score"] < 10  # partial points, not all or nothing
    names = [test["name"] for test in result["tests"]]
    assert "room: reach" in names and "hidden variant 1: reach" in names
    assert not any("hidden-room" in json.dumps(test) for test in result["tests"])
    assert all(test["status"] in ("pass", "fail", "error") for test in result["tests"])
    several = grade_cli(lesson, tmp_path, "--classroom", output)
    assert several.returncode == 2 and "--classroom grades a single program" in several.stderr


def test_the_json_keeps_what_each_visible_variant_printed_trimmed_and_marked(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "chatty.py", CHATTY.format(n=OUTPUT_LINE_CHARS))
    write_program(tmp_path / "class", "quiet.py", CHATTY.format(n=1).replace("range(300)", "range(3)"))
    grade_cli(lesson, tmp_path / "class", "--json", tmp_path / "r.json", "--quiet")
    submissions = {
        Path(s["submission"]).name: s for s in json.loads((tmp_path / "r.json").read_text())["submissions"]
    }
    [visible, hidden] = submissions["chatty.py"]["variants"]
    assert len(visible["output"]) == OUTPUT_HEAD + OUTPUT_TAIL
    assert (
        visible["output_trimmed"] is True
        and visible["output_lines_dropped"] == 300 - OUTPUT_HEAD - OUTPUT_TAIL
    )
    assert " line 0 " in visible["output"][0] and " line 299 " in visible["output"][-1]
    assert all(line.endswith("…") for line in visible["output"])  # each line cut
    assert hidden["hidden"] and hidden["output"] is None  # it could print what it senses of the hidden world
    [quiet, _] = submissions["quiet.py"]["variants"]
    assert [line.split("s  ", 1)[1] for line in quiet["output"]] == ["line 0 x", "line 1 x", "line 2 x"]
    assert quiet["output_trimmed"] is False and quiet["output_lines_dropped"] == 0


def test_a_syntax_error_is_reported_once_with_its_line_and_a_caret(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")  # two variants
    prog = write_program(tmp_path, "broken.py", SYNTAX_ERROR)
    done = grade_cli(lesson, prog, "--json", tmp_path / "r.json")
    assert done.returncode == 1
    assert done.stdout.count("invalid syntax") == 1, done.stdout
    lines = done.stdout.splitlines()
    at = next(i for i, line in enumerate(lines) if "line 3: invalid syntax" in line)
    source, caret = lines[at + 1], lines[at + 2]
    assert source.strip() == "print('a' +)"
    assert caret.strip() == "^" and caret.index("^") == source.index(")")  # under the column, as Python
    saved = json.loads((tmp_path / "r.json").read_text())["submissions"][0]
    assert (
        saved["status"] == "error" and saved["score"] == 0 and saved["problem"].count("invalid syntax") == 1
    )


def test_exit_codes_are_in_the_help_and_hold(tmp_path):
    help_text = grade_cli("--help").stdout
    for code, meaning in (
        ("0", "every program scored"),
        ("1", "some program scored less"),
        ("2", "usage"),
        ("4", "internal error"),
    ):
        assert any(line.split()[:1] == [code] and meaning in line for line in help_text.splitlines()), code
    lesson = write_lesson(tmp_path / "lesson")
    write_program(tmp_path / "class", "alice.py", GOOD)
    assert grade_cli(lesson, tmp_path / "class", "--quiet").returncode == 0  # all passed
    write_program(tmp_path / "class", "bob.py", SHORT)
    assert grade_cli(lesson, tmp_path / "class", "--quiet").returncode == 1  # a class with a failure
    assert grade_cli(lesson, tmp_path / "class", "--jobs", "0").returncode == 2  # usage


def test_grade_into_a_pipe_that_closes_ends_quietly(tmp_path):
    lesson = write_lesson(tmp_path / "lesson")
    for name in ("alice", "bob", "carol"):
        write_program(tmp_path / "class", f"{name}.py", GOOD)
    command = f"{sys.executable} -m ev3sim2d grade {lesson} {tmp_path / 'class'} --details --quiet"
    head = subprocess.run(
        ["bash", "-c", f"{command} | head -1"], capture_output=True, text=True, cwd=ROOT, timeout=300
    )
    assert head.stdout.startswith(str(tmp_path / "class")), head.stdout
    assert "Traceback" not in head.stderr and "BrokenPipe" not in head.stderr, head.stderr
    # a reader gone before anything is written: the writer ends with 141, as `yes | true` does
    gone = subprocess.run(
        ["bash", "-c", f'{command} | true; echo "status=${{PIPESTATUS[0]}}"'],
        capture_output=True,
        text=True,
        cwd=ROOT,
        timeout=300,
    )
    assert gone.stdout.strip() == "status=141", gone.stdout + gone.stderr
    assert "Traceback" not in gone.stderr and "BrokenPipe" not in gone.stderr, gone.stderr


def test_other_commands_into_a_closed_pipe_end_quietly():
    for command in ("mazes", "lessons", f"run {ROOT / 'examples' / 'drive_square.py'} --time 2"):
        done = subprocess.run(
            ["bash", "-c", f"{sys.executable} -m ev3sim2d {command} | true"],
            capture_output=True,
            text=True,
            cwd=ROOT,
            timeout=300,
        )
        assert "Traceback" not in done.stderr and "BrokenPipe" not in done.stderr, (command, done.stderr)


def test_the_docs_say_the_sizes_and_exit_codes_as_they_are():
    lessons = " ".join((ROOT / "docs" / "lessons.md").read_text().split())
    assert f"first {OUTPUT_HEAD} and the last {OUTPUT_TAIL} lines" in lessons
    assert f"cuts a line at {OUTPUT_LINE_CHARS} characters" in lessons
    from ev3sim2d.commands.exit_codes import EXIT_BROKEN_PIPE, EXIT_INTERNAL, EXIT_USAGE

    assert (
        f"{EXIT_USAGE} for a usage error" in lessons and f"{EXIT_INTERNAL} for an internal error" in lessons
    )
    assert f"{EXIT_BROKEN_PIPE} when the reader of its output went away" in lessons
