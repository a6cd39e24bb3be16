"""`ev3sim2d init vscode|pycharm`: the files an editor needs to run the open file in ev3sim2d.

VS Code's files are JSON with comments; the ones it makes begin with a comment and students add their
own tasks.  What is there stays byte for byte, and a second init changes nothing.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import pytest

from ev3sim2d import cli
from ev3sim2d.commands import init
from ev3sim2d.commands.jsonc_file import JsoncError, parse

VSCODE_TASKS = """// See https://go.microsoft.com/fwlink/?LinkId=733558
// for the documentation about the tasks.json format
{
\t"version": "2.0.0",
\t"tasks": [
\t\t{
\t\t\t"label": "copy to the brick",  /* a student's own task, with its own comment */
\t\t\t"type": "shell",
\t\t\t"command": "scp ${file} robot@ev3dev.local:",
\t\t},
\t],
}
"""


def _init(folder, *args) -> int:
    return cli.main(["init", *args, "--folder", str(folder)])


def test_a_project_without_vscode_files_gets_all_three(tmp_path, capsys):
    assert _init(tmp_path, "vscode") == 0
    tasks = json.loads((tmp_path / ".vscode" / "tasks.json").read_text())  # (new files are plain JSON)
    launch = json.loads((tmp_path / ".vscode" / "launch.json").read_text())
    settings = json.loads((tmp_path / ".vscode" / "settings.json").read_text())
    assert tasks["version"] == "2.0.0" and launch["version"] == "0.2.0"
    run = next(t for t in tasks["tasks"] if t["label"] == "run in ev3sim2d")
    assert run["command"] == "${command:python.interpreterPath}"
    assert run["args"] == ["-m", "ev3sim2d", "run", "${file}", "--maze", "${config:ev3sim2d.world}"]
    assert run["group"] == {"kind": "build", "isDefault": True}
    assert run["problemMatcher"]["pattern"]["regexp"]
    live = next(t for t in tasks["tasks"] if t["label"] == "run in ev3sim2d live")
    assert live["args"][2:4] == ["live", "${file}"]
    assert [c["name"] for c in launch["configurations"]] == ["debug in ev3sim2d", "run in ev3sim2d"]
    token = settings.pop("ev3sim2d.debugToken")  # the project's own, new each time a project gets one
    assert len(token) >= 20 and settings == {"ev3sim2d.world": "line"}  # the one place the world is named
    assert "written" in capsys.readouterr().out


def test_it_adds_to_files_vs_code_made_and_keeps_every_byte_of_them(tmp_path):
    folder = tmp_path / ".vscode"
    folder.mkdir()
    (folder / "tasks.json").write_text(VSCODE_TASKS)
    (folder / "settings.json").write_text('{\n  // mine\n  "editor.fontSize": 16,\n}\n')
    assert _init(tmp_path, "vscode", "--world", "maze") == 0
    tasks_text = (folder / "tasks.json").read_text()
    for line in VSCODE_TASKS.splitlines():  # every line of the student's file, in order
        assert line in tasks_text
    tasks = parse(tasks_text)
    assert [t["label"] for t in tasks["tasks"]] == [
        "run in ev3sim2d",
        "run in ev3sim2d live",
        "ev3sim2d debug server",
        "copy to the brick",
    ]
    settings = parse((folder / "settings.json").read_text())
    assert settings.pop("ev3sim2d.debugToken") and settings == {"ev3sim2d.world": "maze", "editor.fontSize": 16}
    before = {name: (folder / name).read_bytes() for name in ("tasks.json", "launch.json", "settings.json")}
    assert _init(tmp_path, "vscode") == 0  # a second time: nothing changes
    assert {name: (folder / name).read_bytes() for name in before} == before


def test_a_students_own_task_of_that_name_and_own_world_stay(tmp_path):
    folder = tmp_path / ".vscode"
    folder.mkdir()
    mine = {"version": "2.0.0", "tasks": [{"label": "run in ev3sim2d", "type": "shell", "command": "my own"}]}
    (folder / "tasks.json").write_text(json.dumps(mine))
    (folder / "settings.json").write_text('{"ev3sim2d.world": "sumo"}')
    assert _init(tmp_path, "vscode") == 0
    tasks = parse((folder / "tasks.json").read_text())["tasks"]
    assert tasks[-1] == mine["tasks"][0] and [t["label"] for t in tasks] == [
        "run in ev3sim2d live",
        "ev3sim2d debug server",
        "run in ev3sim2d",
    ]
    settings = parse((folder / "settings.json").read_text())
    assert settings.pop("ev3sim2d.debugToken") and settings == {"ev3sim2d.world": "sumo"}


def test_a_broken_file_is_named_with_its_line_and_nothing_is_written(tmp_path, capsys):
    folder = tmp_path / ".vscode"
    folder.mkdir()
    (folder / "launch.json").write_text('{\n  "version": "0.2.0"\n  "configurations": []\n}\n')
    assert _init(tmp_path, "vscode") == 2
    err = capsys.readouterr().err
    assert "launch.json: line 3:" in err and "run init again" in err
    assert sorted(p.name for p in folder.iterdir()) == ["launch.json"]


def test_a_world_that_is_not_there_is_refused(tmp_path, capsys):
    assert _init(tmp_path, "vscode", "--world", "nosuch") == 2
    assert "--world nosuch" in capsys.readouterr().err
    assert not (tmp_path / ".vscode").exists()


def test_pycharm_gets_a_run_configuration_for_the_current_file_once(tmp_path):
    assert _init(tmp_path, "pycharm", "--world", "maze") == 0
    path = tmp_path / ".idea" / "runConfigurations" / "run_in_ev3sim2d.xml"
    configuration = ElementTree.parse(path).getroot().find("configuration")
    options = {o.get("name"): o.get("value") for o in configuration.findall("option")}
    assert configuration.get("type") == "PythonConfigurationType"
    assert options["MODULE_MODE"] == "true" and options["SCRIPT_NAME"] == "ev3sim2d"
    assert options["PARAMETERS"] == 'run "$FilePath$" --maze "maze"'
    path.write_text("<mine/>")
    assert _init(tmp_path, "pycharm") == 0 and path.read_text() == "<mine/>"


@pytest.mark.parametrize(
    "text",
    ['{"a": [1, 2,], /* c */ "b": "x//y"}', '// top\n{"a": [1, 2], "b": "x//y"}', '{"a":[1,2],"b":"x//y"}'],
)
def test_json_with_comments_reads_as_vs_code_reads_it(text):
    assert parse(text) == {"a": [1, 2], "b": "x//y"}


def test_json_with_comments_says_where_it_is_broken():
    with pytest.raises(JsoncError) as caught:
        parse('{\n  "a": 1,\n  "b" 2\n}')
    assert caught.value.line == 3


def test_the_tasks_problem_matcher_is_the_one_the_run_lines_are_made_for():
    from ev3sim2d.commands.problem_lines import PATTERN

    assert all(t["problemMatcher"]["pattern"]["regexp"] == PATTERN for t in init.vscode_tasks())


def test_f5_starts_the_debug_server_and_attaches_with_the_projects_token(tmp_path):
    """The launch configuration's pre-launch task runs the file with --debug-adapter on the port it
    attaches to, with the token from settings.json; VS Code attaches once the task's background pattern
    sees the run's waiting line."""
    assert _init(tmp_path, "vscode") == 0
    folder = tmp_path / ".vscode"
    launch = next(
        c for c in parse((folder / "launch.json").read_text())["configurations"] if c["request"] == "attach"
    )
    server = next(
        t
        for t in parse((folder / "tasks.json").read_text())["tasks"]
        if t["label"] == launch["preLaunchTask"]
    )
    assert launch["type"] == "debugpy" and launch["connect"]["host"] == "127.0.0.1"
    args = server["args"]
    assert args[args.index("--debug-adapter") + 1] == str(launch["connect"]["port"])
    assert args[args.index("--debug-token") + 1] == launch["ev3sim2dToken"] == "${config:ev3sim2d.debugToken}"
    assert server["isBackground"] is True
    program = tmp_path / "prog.py"
    program.write_text("print('hi')\n")
    run = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--debug-adapter", "0"],
        stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        waiting = run.stderr.readline()
    finally:
        run.kill()
        run.wait()
    background = server["problemMatcher"]["background"]
    assert re.search(background["beginsPattern"], waiting) and re.search(background["endsPattern"], waiting)
