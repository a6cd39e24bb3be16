"""Files written on Windows, macOS and Linux, swapped between students, run as plain Python runs them.

Programs with a UTF-8 BOM, Windows line endings or a PEP 263 coding line; world, robot and lesson files
with a BOM and Windows line endings; paths inside files written with '\\'; folders with spaces and
letters beyond ASCII; and every message naming a file the way the student named it.  Runs go through
the real command line, from the folder the student works in.
"""

import codecs
import io
import json
import os
import subprocess
import sys
import tokenize
from pathlib import Path

import pytest

from ev3sim2d.brick import program as brick_program
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.simulator.run import run_programs, start_failure
from ev3sim2d.world.maze_file import load_maze
from ev3sim2d.world.source_error import WorldFileError
from tests.grading.lesson_maker import GOOD, ROOM

ROOT = Path(__file__).resolve().parents[1]

DRIVE = """\
from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)
print("done")
"""

ROOM_WORLD = """\
# A small walled room, written on another computer.
title: Room
cell_cm: 10
grid: |
  ##########
  #........#
  #........#
  #........#
  #........#
  #........#
  ##########
start: {{cell: [3, 3], heading_deg: 0}}
{robot}"""
"""A world file's text: the grid's rows are lines 5 to 11, the start line 12, the robot's line 13."""

ROBOT_ON_A_AND_D = """\
# A robot whose wheels are on ports A and D, unlike the driving base's B and C.
name: A and D
wheel_diameter_mm: 56
axle_track_mm: 120
body: {front_cm: 9, back_cm: 7, width_cm: 15}
motors:
  - {port: A, kind: large, wheel: left}
  - {port: D, kind: large, wheel: right}
sensors:
  - {port: 1, kind: touch, angle_deg: 0, radius_cm: 9, facing: forward}
"""

DRIVE_A_AND_D = """\
from ev3dev2.motor import MoveTank, OUTPUT_A, OUTPUT_D
MoveTank(OUTPUT_A, OUTPUT_D).on_for_seconds(30, 30, 1)
"""
"""Finishes only on the robot of ROBOT_ON_A_AND_D: the driving base has no motor on A or D."""


def from_windows(text: str) -> bytes:
    """The text as Notepad saves it: a UTF-8 BOM and "\\r\\n" line endings."""
    return codecs.BOM_UTF8 + text.replace("\n", "\r\n").encode("utf-8")


def ev3sim2d(*args, cwd: Path) -> subprocess.CompletedProcess:
    """`ev3sim2d ARGS` in the folder `cwd`, as a student types it (the console in UTF-8 on any system)."""
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *map(str, args)],
        capture_output=True,
        encoding="utf-8",
        cwd=cwd,
        env={**os.environ, "PYTHONUTF8": "1"},
        timeout=120,
    )


def summary_of(cwd: Path, name: str = "out.json") -> dict:
    return json.loads((cwd / name).read_text(encoding="utf-8"))


def load_maze_text(folder: Path, text: str):
    """The world of a world file with this text, written into `folder`."""
    path = folder / "world.yaml"
    path.write_text(text, encoding="utf-8")
    return load_maze(path)


# -- programs ---------------------------------------------------------------------------------


def test_a_program_saved_with_a_bom_and_windows_line_endings_runs(tmp_path):
    (tmp_path / "prog.py").write_bytes(from_windows(DRIVE))
    result = ev3sim2d("run", "prog.py", "--time", "3", "--summary", "out.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    summary = summary_of(tmp_path)
    assert summary["status"] == "finished" and summary["output"] == ["done"]
    assert summary["robots"][0]["path_cm"] > 5


def test_a_cp1252_program_with_a_coding_line_prints_its_accents(tmp_path):
    source = '# -*- coding: cp1252 -*-\r\nname = "café"\r\nprint(name, len(name))\r\n'
    (tmp_path / "prog.py").write_bytes(source.encode("cp1252"))
    result = ev3sim2d("run", "prog.py", "--time", "1", "--summary", "out.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "café 4" in result.stdout
    assert summary_of(tmp_path)["output"] == ["café 4"]


def test_a_program_with_old_mac_line_endings_and_a_coding_line_on_line_two_runs(tmp_path):
    source = "#!/usr/bin/env python3\r# vim: set fileencoding=latin-1 :\rprint('Grüße')\r"
    (tmp_path / "prog.py").write_bytes(source.encode("latin-1"))
    result = ev3sim2d("run", "prog.py", "--time", "1", "--summary", "out.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert summary_of(tmp_path)["output"] == ["Grüße"]


def test_a_cp1252_program_without_a_coding_line_is_refused_with_its_line_and_the_fix(tmp_path):
    (tmp_path / "prog.py").write_bytes(b'x = 1\r\n# le caf\xe9\r\nprint("caf\xe9")\r\n')
    result = ev3sim2d("run", "prog.py", "--time", "1", cwd=tmp_path)
    assert result.returncode == 1
    assert "prog.py, line 2: byte 0xe9 is not UTF-8 text" in result.stderr  # the comment's byte, as Python
    assert "save the file as UTF-8, or add `# -*- coding: cp1252 -*-` as its first line" in result.stderr
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize(
    ("data", "said"),
    [
        (b"# coding: klingon\nx = 1\n", "line 1: unknown encoding 'klingon' in the coding line"),
        (b"# coding: ascii\nx = '\xc3\xa9'\n", "line 2: byte 0xc3 is not ascii text, as the coding line"),
        (codecs.BOM_UTF8 + b"# coding: latin-1\n", "line 1: the file starts with a UTF-8 mark (BOM)"),
        (codecs.BOM_UTF16_LE + "print(1)\n".encode("utf-16-le"), "line 1: the file is saved as UTF-16"),
        ("x = 1\nprint(2)\n".encode("utf-16-le"), "line 1: a null byte: this is not a Python text file"),
    ],
)
def test_a_program_python_cannot_read_as_text_says_why_and_what_to_do(tmp_path, monkeypatch, data, said):
    (tmp_path / "prog.py").write_bytes(data)
    monkeypatch.chdir(tmp_path)
    result = run_programs(["prog.py"], load_maze_text(tmp_path, ROOM_WORLD.format(robot="")), time_limit_s=2)
    told = start_failure(result)  # (its brick found it: only a brick reads a program's source)
    assert told is not None and said in told and "save the file" in told


@pytest.mark.parametrize(
    "data",
    [
        b"print('plain')\n",
        from_windows("print('caf\u00e9')\n"),
        "# -*- coding: cp1252 -*-\nprint('café')\n".encode("cp1252"),
        b"x = 1\n# caf\xe9\n",
        b"# coding: klingon\n",
        codecs.BOM_UTF8 + b"# coding: latin-1\n",
        codecs.BOM_UTF16_BE + "x = 1\n".encode("utf-16-be"),
        b"x = 1\r\n\x00",
    ],
)
def test_the_brick_reads_a_program_file_as_python_reads_it(data):
    """What the brick makes of a file's bytes is what Python makes of them: the same text where Python
    compiles it, a SyntaxError where Python refuses it (and, beyond Python, a bad byte in a comment)."""
    try:
        text = brick_program.source_text(data, "prog.py")
    except SyntaxError:
        text = None
    try:
        compile(data, "prog.py", "exec")
        encoding = tokenize.detect_encoding(io.BytesIO(data).readline)[0]
        python = data.decode(encoding).removeprefix("\ufeff")
    except (SyntaxError, ValueError):
        python = None
    if python is None or data == b"x = 1\n# caf\xe9\n":  # (Python lets a bad byte in a comment pass)
        assert text is None
    else:
        assert text == python


def test_the_brick_refuses_a_cp1252_program_with_the_line_and_the_fix(tmp_path, monkeypatch):
    """The brick, which alone compiles a program, says where and what to do."""
    (tmp_path / "prog.py").write_bytes(b"import time\ntime.sleep(1)\nprint('caf\xe9')\n")
    monkeypatch.chdir(tmp_path)
    result = run_programs(["prog.py"], load_maze_text(tmp_path, ROOM_WORLD.format(robot="")), time_limit_s=2)
    assert result.status == "error"
    assert result.error["type"] == "SyntaxError" and result.error["compiling"]
    assert result.error["file"] == "prog.py" and result.error["line"] == 3
    assert "save the file as UTF-8, or add `# -*- coding: cp1252 -*-`" in result.error["message"]
    assert result.error["traceback"].startswith('  File "prog.py", line 3\n')  # as Python shows it
    assert str(tmp_path) not in result.error["traceback"]


# -- world, robot and lesson files ----------------------------------------------------------------


def test_world_and_robot_files_saved_with_a_bom_and_windows_line_endings_load(tmp_path):
    (tmp_path / "bot.yaml").write_bytes(from_windows(ROBOT_ON_A_AND_D))
    (tmp_path / "room.yaml").write_bytes(from_windows(ROOM_WORLD.format(robot="robot: bot.yaml\n")))
    (tmp_path / "prog.py").write_text(DRIVE_A_AND_D)
    result = ev3sim2d("run", "prog.py", "--maze", "room.yaml", "--summary", "out.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert summary_of(tmp_path)["status"] == "finished"
    world = load_maze(tmp_path / "room.yaml")
    assert world.description == "A small walled room, written on another computer."  # the BOM is not text
    assert world.robot.name == "A and D" and "\r" not in world.text


@pytest.mark.parametrize("saved", [from_windows, lambda text: text.replace("\n", "\r").encode()])
def test_a_mistake_in_a_world_file_from_windows_names_its_line_and_column(tmp_path, saved):
    text = ROOM_WORLD.format(robot="").replace("  #........#\n", "  #.Q......#\n", 1)
    (tmp_path / "room.yaml").write_bytes(saved(text))
    (tmp_path / "prog.py").write_text("pass\n")
    result = ev3sim2d("run", "prog.py", "--maze", "room.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert "room.yaml:6:5: unknown cell character 'Q'" in result.stderr


def test_a_mistake_in_a_robot_file_from_windows_names_its_line_and_column(tmp_path):
    (tmp_path / "bot.yaml").write_bytes(from_windows(ROBOT_ON_A_AND_D.replace("kind: touch", "kind: tuoch")))
    (tmp_path / "room.yaml").write_bytes(from_windows(ROOM_WORLD.format(robot="robot: bot.yaml\n")))
    (tmp_path / "prog.py").write_text("pass\n")
    result = ev3sim2d("run", "prog.py", "--maze", "room.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert "bot.yaml:10:21: unknown kind 'tuoch'" in result.stderr


def test_a_yaml_syntax_error_on_the_first_line_after_a_bom_counts_columns_as_an_editor_does(tmp_path):
    (tmp_path / "room.yaml").write_bytes(from_windows("title: a: b\n"))
    with pytest.raises(WorldFileError) as caught:
        load_maze(tmp_path / "room.yaml")
    assert (caught.value.line, caught.value.column) == (1, 9)


def test_a_cp1252_world_file_names_the_line_of_its_first_bad_byte_and_the_fix(tmp_path):
    text = ROOM_WORLD.format(robot="").replace("title: Room", "title: Café")
    (tmp_path / "room.yaml").write_bytes(text.replace("\n", "\r\n").encode("cp1252"))
    (tmp_path / "prog.py").write_text("pass\n")
    result = ev3sim2d("run", "prog.py", "--maze", "room.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert "room.yaml:2:11: byte 0xe9 is not UTF-8 text" in result.stderr
    assert "save the file as UTF-8" in result.stderr and "Traceback" not in result.stderr


def test_a_cp1252_robot_file_names_its_line_too(tmp_path):
    (tmp_path / "bot.yaml").write_bytes(
        ROBOT_ON_A_AND_D.replace("name: A and D", "name: Müller").encode("cp1252")
    )
    (tmp_path / "room.yaml").write_text(ROOM_WORLD.format(robot="robot: bot.yaml\n"))
    with pytest.raises(WorldFileError, match=r"bot\.yaml:2:8: byte 0xfc is not UTF-8 text.*save the file"):
        load_maze(tmp_path / "room.yaml")


def a_lesson(folder: Path, lesson_text: str, save=lambda text: text.encode()) -> Path:
    """A lesson whose files live in sub-folders; every file written by `save`."""
    two_starts = "start:\n  - {x_cm: 25, y_cm: 35, heading_deg: 0}\n  - {x_cm: 70, y_cm: 20, heading_deg: 0}"
    files = {
        "lesson.yaml": lesson_text,
        "worlds/room.yaml": ROOM.replace("start: {x_cm: 25, y_cm: 35, heading_deg: 0}", two_starts),
        "robots/my bot.yaml": ROBOT_ON_A_AND_D,
        "programs/starter.py": GOOD,
        "programs/pacer.py": "pass\n",
        "hidden/hidden.yaml": "variants:\n  - name: again\n    world: worlds\\room.yaml\n",
    }
    for name, text in files.items():
        (folder / name).parent.mkdir(parents=True, exist_ok=True)
        (folder / name).write_bytes(save(text))
    return folder


LESSON_FROM_WINDOWS = """\
title: Reach the goal
goal: Drive 30 cm ahead into the green goal and stop there.
time_s: 5
robot: robots\\my bot.yaml
starter: programs\\starter.py
others: [{name: pacer, program: programs\\pacer.py, start: 2}]
variants:
  - name: room
    world: worlds\\room.yaml
checks:
  - {kind: reach_region, region: goal, goal: true}
"""


def test_a_lesson_saved_on_windows_with_backslash_paths_loads_on_every_system(tmp_path):
    folder = a_lesson(tmp_path / "lesson", LESSON_FROM_WINDOWS, from_windows)
    lesson = load_lesson(folder)
    assert [v.world_path for v in lesson.variants] == [folder / "worlds" / "room.yaml"] * 2
    assert lesson.variants[0].world().robot.name == "A and D"
    assert lesson.starter == folder / "programs" / "starter.py"
    assert lesson.others[0].program == folder / "programs" / "pacer.py"
    result = ev3sim2d("lessons", "--dir", folder, cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert "Reach the goal: Drive 30 cm ahead" in result.stdout


def test_a_mistake_in_a_lesson_file_from_windows_names_its_line(tmp_path):
    text = LESSON_FROM_WINDOWS.replace("time_s: 5", "time_s: soon")
    with pytest.raises(WorldFileError) as caught:
        load_lesson(a_lesson(tmp_path / "lesson", text, from_windows))
    assert (caught.value.line, caught.value.column) == (3, 9)


def test_a_cp1252_lesson_file_names_its_line(tmp_path):
    text = LESSON_FROM_WINDOWS.replace("into the green goal", "into the café")
    with pytest.raises(WorldFileError, match=r"lesson\.yaml:2:\d+: byte 0xe9 is not UTF-8 text"):
        load_lesson(a_lesson(tmp_path / "lesson", text, lambda text: text.encode("cp1252")))


# -- paths written inside files -------------------------------------------------------------------


@pytest.mark.parametrize("written", ["sub\\bot.yaml", "robots\\my bot.yaml", "robots/my bot.yaml"])
def test_a_world_file_names_its_robot_file_with_either_separator(tmp_path, written):
    robot_file = tmp_path / written.replace("\\", "/")
    robot_file.parent.mkdir(parents=True, exist_ok=True)
    robot_file.write_text(ROBOT_ON_A_AND_D)
    (tmp_path / "room.yaml").write_text(ROOM_WORLD.format(robot=f"robot: {written}\n"))
    (tmp_path / "prog.py").write_text(DRIVE_A_AND_D)
    result = ev3sim2d("run", "prog.py", "--maze", "room.yaml", "--summary", "out.json", cwd=tmp_path)
    assert result.returncode == 0, result.stderr
    assert summary_of(tmp_path)["status"] == "finished"


def test_a_start_names_its_robot_file_with_a_backslash_too(tmp_path):
    (tmp_path / "robots").mkdir()
    (tmp_path / "robots" / "bot.yaml").write_text(ROBOT_ON_A_AND_D)
    text = ROOM_WORLD.format(robot="").replace(
        "start: {cell: [3, 3], heading_deg: 0}", "start: {cell: [3, 3], robot: robots\\bot.yaml}"
    )
    world = load_maze_text(tmp_path, text)
    assert world.start_robot(0).name == "A and D"


def test_a_backslash_in_double_quotes_says_how_to_write_the_path(tmp_path):
    text = ROOM_WORLD.format(robot='robot: "robots\\my bot.yaml"\n')
    with pytest.raises(
        WorldFileError, match="write a path with '/' instead of '\\\\', or in 'single quotes'"
    ):
        load_maze_text(tmp_path, text)


@pytest.mark.skipif(os.name == "nt", reason="C:\\ is a path of this computer on Windows")
def test_an_absolute_windows_path_is_not_found_elsewhere_and_says_so(tmp_path):
    text = ROOM_WORLD.format(robot="robot: C:\\Users\\ana\\robots\\bot.yaml\n")
    with pytest.raises(WorldFileError) as caught:
        load_maze_text(tmp_path, text)
    assert caught.value.line == 13
    assert "'C:\\Users\\ana\\robots\\bot.yaml' is a path on another computer" in caught.value.message


# -- folders with spaces and letters beyond ASCII ------------------------------------------------------


def test_a_program_and_world_in_a_folder_named_with_spaces_and_umlauts_run_the_same(tmp_path):
    prints = []
    for folder in (tmp_path / "plain", tmp_path / "my robot ä" / "Übung 1"):
        (folder / "robots").mkdir(parents=True)
        (folder / "robots" / "my bot.yaml").write_text(ROBOT_ON_A_AND_D, encoding="utf-8")
        (folder / "room.yaml").write_text(ROOM_WORLD.format(robot="robot: robots/my bot.yaml\n"))
        (folder / "prog.py").write_text(DRIVE_A_AND_D)
        given = folder.relative_to(tmp_path)
        result = ev3sim2d(
            "run",
            given / "prog.py",
            "--maze",
            given / "room.yaml",
            "--summary",
            given / "out.json",
            cwd=tmp_path,
        )
        assert result.returncode == 0, result.stderr
        summary = summary_of(folder)
        assert summary["status"] == "finished"
        prints.append(summary["fingerprint"])
        result = run_programs([folder / "prog.py"], load_maze(folder / "room.yaml"), time_limit_s=3)
        prints.append(result.trace.fingerprint())
    assert len(set(prints)) == 1


# -- file:line as the student gave it ---------------------------------------------------------------


def test_a_syntax_error_names_the_program_as_given(tmp_path):
    (tmp_path / "sub dir").mkdir()
    (tmp_path / "sub dir" / "prog.py").write_bytes(from_windows("x = 1\nprint('a'\n"))
    result = ev3sim2d("run", "sub dir/prog.py", "--time", "1", cwd=tmp_path)
    assert result.returncode == 1
    assert f"sub dir{os.sep}prog.py, line 2: '(' was never closed" in result.stderr
    assert str(tmp_path) not in result.stderr


def test_a_runtime_error_names_the_program_as_given_in_the_traceback_and_the_report(tmp_path):
    (tmp_path / "sub dir").mkdir()
    source = "# -*- coding: cp1252 -*-\nimport time\ntime.sleep(0.5)\n{}['caf\xe9']\n"
    (tmp_path / "sub dir" / "prog.py").write_bytes(source.replace("\n", "\r\n").encode("cp1252"))
    result = ev3sim2d("run", "sub dir/prog.py", "--summary", "out.json", cwd=tmp_path)
    shown = f"sub dir{os.sep}prog.py"
    assert result.returncode == 1
    assert f'File "{shown}", line 4, in <module>' in result.stderr
    assert "{}['café']" in result.stderr  # the line, read back in the file's own encoding
    error = summary_of(tmp_path)["error"]
    assert error["file"] == shown and error["line"] == 4
    assert f"KeyError: 'café' ({shown}, line 4, at 0.50 s)" in summary_of(tmp_path)["reason"]
    assert str(tmp_path) not in result.stderr + json.dumps(error)


def test_a_world_file_error_names_the_world_file_as_given(tmp_path):
    (tmp_path / "sub dir").mkdir()
    text = ROOM_WORLD.format(robot="").replace("  #........#\n", "  #.Q......#\n", 1)
    (tmp_path / "sub dir" / "room.yaml").write_bytes(from_windows(text))
    (tmp_path / "prog.py").write_text("pass\n")
    result = ev3sim2d("run", "prog.py", "--maze", "sub dir/room.yaml", cwd=tmp_path)
    assert result.returncode == 2
    assert f"sub dir{os.sep}room.yaml:6:5: unknown cell character 'Q'" in result.stderr
    assert str(tmp_path) not in result.stderr
