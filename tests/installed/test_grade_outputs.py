"""`ev3sim2d grade` installed, as a teacher runs it on a class from a folder of their own: a shipped lesson
with the hidden variants from the teacher's copy (the repository's lessons/wall-stop/hidden), and the
outputs a Classroom, a CI job and Excel read (the same checks as tests/grading/test_grade_outputs.py,
which builds its own lessons and runs the checkout)."""

import json
import os
import shutil
import xml.etree.ElementTree as ET

import pytest

from ev3sim2d.grading.result import OUTPUT_HEAD, OUTPUT_LINE_CHARS, OUTPUT_TAIL
from tests.grading.test_grade_outputs import JUNIT_XSD_ATTRIBUTES, JUNIT_XSD_CHILDREN
from tests.installed.installed_venv import ROOT

LESSON = ROOT / "lessons" / "wall-stop"
SYNTAX_ERROR = "x = 1\nif x:\n    print('a' +)\n"
CHATTY = f"for i in range(300):\n    print('line', i, 'x' * {OUTPUT_LINE_CHARS})\n"


@pytest.fixture
def a_class(user_folder):
    """Four students: one who solved it, one who handed in the starter, one whose program does not parse,
    and one whose program only prints, a lot."""
    class_folder = user_folder / "class"
    class_folder.mkdir()
    shutil.copy(LESSON / "solution.py", class_folder / "jürgen.py")
    shutil.copy(LESSON / "starter.py", class_folder / "ana.py")
    (class_folder / "carl.py").write_text(SYNTAX_ERROR)
    (class_folder / "dora.py").write_text(CHATTY)
    return class_folder


def test_a_class_graded_with_hidden_variants_into_csv_junit_and_json(installed, user_folder, a_class):
    done = installed.run(
        "ev3sim2d", "grade", "wall-stop", "class", "--hidden", str(LESSON / "hidden"),
        "--csv", "class.csv", "--junit", "class.xml", "--json", "class.json", cwd=user_folder,
    )  # fmt: skip
    assert done.returncode == 1, done.stderr  # a class with failures
    assert "Traceback" not in done.stderr

    csv = (user_folder / "class.csv").read_bytes()
    assert csv.startswith(b"\xef\xbb\xbfsubmission,")  # Excel reads it as UTF-8
    assert "jürgen.py".encode() in csv

    root = ET.parse(user_folder / "class.xml").getroot()
    for element in root.iter():
        assert set(element.attrib) <= JUNIT_XSD_ATTRIBUTES[element.tag], (element.tag, element.attrib)
        assert {child.tag for child in element} <= JUNIT_XSD_CHILDREN.get(element.tag, set()), element.tag
    assert root.get("failures") != "0" and root.get("errors") == "1"

    submissions = {  # (a class folder's programs are named by their paths: class\ana.py on Windows)
        s["submission"].replace(os.sep, "/"): s
        for s in json.loads((user_folder / "class.json").read_text(encoding="utf-8"))["submissions"]
    }
    solved = submissions["class/jürgen.py"]
    assert solved["score"] == solved["max_score"] == 40  # 10 points a variant
    visible, *hidden = solved["variants"]
    assert len(hidden) == 3 and all(variant["hidden"] and variant["output"] is None for variant in hidden)
    assert visible["output"][-1].endswith("cm from the wall") and visible["output_trimmed"] is False
    assert 0 == submissions["class/ana.py"]["score"] < submissions["class/ana.py"]["max_score"]
    broken = submissions["class/carl.py"]
    assert broken["status"] == "error" and broken["problem"].count("invalid syntax") == 1
    chatty, *_ = submissions["class/dora.py"]["variants"]
    assert len(chatty["output"]) == OUTPUT_HEAD + OUTPUT_TAIL and chatty["output_trimmed"] is True
    assert chatty["output_lines_dropped"] == 300 - OUTPUT_HEAD - OUTPUT_TAIL


def test_a_syntax_error_is_said_once_with_its_line_and_a_caret(installed, user_folder, a_class):
    done = installed.run(
        "ev3sim2d", "grade", "wall-stop", "class/carl.py", "--hidden", str(LESSON / "hidden"), cwd=user_folder
    )
    assert done.returncode == 1
    assert done.stdout.count("invalid syntax") == 1, done.stdout  # four variants, said once
    lines = done.stdout.splitlines()
    at = next(i for i, line in enumerate(lines) if "class/carl.py, line 3: invalid syntax" in line)
    source, caret = lines[at + 1], lines[at + 2]
    assert source.strip() == "print('a' +)" and caret.index("^") == source.index(")")


def test_exit_codes_are_in_the_help_and_a_usage_error_is_2(installed, user_folder):
    help_text = installed.run("ev3sim2d", "grade", "--help", cwd=user_folder).stdout
    codes = {line.split()[0] for line in help_text.splitlines() if line[:5].strip().isdigit()}
    assert {"0", "1", "2", "4"} <= codes
    wrong = installed.run("ev3sim2d", "grade", "no-such-lesson", "x.py", cwd=user_folder)
    assert wrong.returncode == 2 and "no-such-lesson" in wrong.stderr and "Traceback" not in wrong.stderr


@pytest.mark.needs_linux("posix_shell", "signals")  # `| head -1`, and SIGPIPE's status 141
def test_grade_into_head_ends_quietly(installed, user_folder, a_class):
    head = installed.run(
        "ev3sim2d grade wall-stop class --details --quiet | head -1", cwd=user_folder, shell=True
    )
    assert head.stdout.startswith("class/"), head.stdout
    assert "Traceback" not in head.stderr and "BrokenPipe" not in head.stderr, head.stderr
    gone = installed.run(
        "bash", "-c", 'ev3sim2d grade wall-stop class --quiet | true; echo "status=${PIPESTATUS[0]}"',
        cwd=user_folder,
    )  # fmt: skip
    assert gone.stdout.strip() == "status=141", gone.stdout + gone.stderr
    assert "Traceback" not in gone.stderr and "BrokenPipe" not in gone.stderr, gone.stderr
