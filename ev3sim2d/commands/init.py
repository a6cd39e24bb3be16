"""`ev3sim2d init vscode|pycharm`: run the file open in the editor in ev3sim2d, with one key.

`init vscode` writes into the project's `.vscode/`:
- tasks.json: "run in ev3sim2d" (the default build task: Ctrl+Shift+B) and "run in ev3sim2d live" (the
  live page, so that the robot is seen driving), each with the Python extension's interpreter, the
  current file, and a problem matcher that reads the run's `FILE:LINE: error: ...` lines
  (problem_lines.py), so that the Problems panel lists the program's error, and where a stuck program was;
- launch.json: F5, "debug in ev3sim2d": the task "ev3sim2d debug server" runs the current file with
  `--debug-adapter`, and VS Code's debugger (the Python extension's debugpy, attaching) connects to it:
  breakpoints, stepping, threads, the stack and variables, while the whole world waits
  (debug_adapter.py); and "run in ev3sim2d", which runs it without;
- settings.json: `ev3sim2d.world`, the world every one of them runs in: the one place to change it;
  and `ev3sim2d.debugToken`, the project's own token, which only its launch configuration gives.
Each is added to a file that exists, as text: nothing a student (or VS Code) wrote is changed, and an
entry of the same name is left as the student has it (jsonc_file.py).

`init pycharm` writes `.idea/runConfigurations/run_in_ev3sim2d.xml`, a run configuration for the current
file (PyCharm's `$FilePath$`), unless one is there.
"""

from __future__ import annotations

import argparse
import secrets
from pathlib import Path
from xml.sax.saxutils import quoteattr

from ..results.output_files import make_folder_in, read_limited, write_file
from ..world.maze_file import find_maze
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_OK, fail
from .jsonc_file import JsoncError, add_key, add_to_array, parse
from .problem_lines import PATTERN

NAME = "init"
HELP = "set up an editor's project to run the open file in ev3sim2d (VS Code's tasks and F5, PyCharm)"
WORLD_SETTING = "ev3sim2d.world"
WORLD = "${config:" + WORLD_SETTING + "}"
PYTHON = "${command:python.interpreterPath}"
RUN_TASK, LIVE_TASK = "run in ev3sim2d", "run in ev3sim2d live"
DEBUG_TASK, DEBUG_LAUNCH = "ev3sim2d debug server", "debug in ev3sim2d"
TOKEN_SETTING = "ev3sim2d.debugToken"
TOKEN = "${config:" + TOKEN_SETTING + "}"
DEBUG_PORT = 5678
WAITING = "^ev3sim2d: waiting for the debugger"  # (the run's line once its debug adapter listens)
MAX_BYTES = 2**20  # an editor's settings file, at most
NEW_FILES = {  # what a file that is not there yet starts as (VS Code wants each file's version)
    "tasks.json": '{\n    "version": "2.0.0",\n    "tasks": []\n}\n',
    "launch.json": '{\n    "version": "0.2.0",\n    "configurations": []\n}\n',
    "settings.json": "{\n}\n",
}

PROBLEM_MATCHER = {
    "owner": "ev3sim2d",
    "source": "ev3sim2d",
    "fileLocation": ["autoDetect", "${workspaceFolder}"],
    "pattern": {"regexp": PATTERN, "file": 1, "line": 2, "severity": 3, "message": 4},
}


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("editor", choices=("vscode", "pycharm"), help="the editor to set up")
    parser.add_argument(
        "--world",
        default="line",
        help="the world the programs run in (a shipped world's name or a world file)",
    )
    parser.add_argument("--folder", default=".", help="the project's folder (default: this one)")


def vscode_tasks() -> list[dict]:
    def task(label: str, command: str, detail: str, default: bool) -> dict:
        return {
            "label": label,
            "detail": detail,
            "type": "process",
            "command": PYTHON,
            "args": ["-m", "ev3sim2d", command, "${file}", "--maze", WORLD],
            "options": {"cwd": "${workspaceFolder}"},
            "group": {"kind": "build", "isDefault": default},
            "presentation": {"reveal": "always", "panel": "dedicated", "clear": True},
            "problemMatcher": PROBLEM_MATCHER,
        }

    server = task(
        DEBUG_TASK, "run", "the current file, waiting for VS Code's debugger (F5: debug in ev3sim2d)", False
    )
    server["args"] += ["--debug-adapter", str(DEBUG_PORT), "--debug-token", TOKEN]
    server["isBackground"] = True
    server["group"] = "none"
    server["problemMatcher"] = {
        **PROBLEM_MATCHER,
        "background": {"activeBegins": True, "beginsPattern": WAITING, "endsPattern": WAITING},
    }
    return [
        task(
            RUN_TASK,
            "run",
            f"the current file, in the world of .vscode/settings.json ({WORLD_SETTING})",
            True,
        ),
        task(LIVE_TASK, "live", "the current file on the live page: the robot drives in the browser", False),
        server,
    ]


def vscode_launches() -> list[dict]:
    return [
        {
            "name": DEBUG_LAUNCH,
            "type": "debugpy",
            "request": "attach",
            "connect": {"host": "127.0.0.1", "port": DEBUG_PORT},
            "preLaunchTask": DEBUG_TASK,
            "ev3sim2dToken": TOKEN,  # (the run lets in only the debugger that gives it: debug_adapter.py)
        },
        {
            "name": RUN_TASK,
            "type": "debugpy",
            "request": "launch",
            "module": "ev3sim2d",
            "args": ["run", "${file}", "--maze", WORLD],
            "cwd": "${workspaceFolder}",
            "console": "integratedTerminal",
            "subProcess": False,  # (the program runs in its own sandboxed brick: no debugger reaches in there)
            "justMyCode": True,
        },
    ]


def pycharm_configuration(world: str) -> str:
    parameters = quoteattr(f'run "$FilePath$" --maze "{world}"')
    return f"""<component name="ProjectRunConfigurationManager">
  <configuration default="false" name="{RUN_TASK}" type="PythonConfigurationType" factoryName="Python">
    <option name="PARENT_ENVS" value="true" />
    <option name="WORKING_DIRECTORY" value="$ProjectFileDir$" />
    <option name="IS_MODULE_SDK" value="true" />
    <option name="ADD_CONTENT_ROOTS" value="true" />
    <option name="ADD_SOURCE_ROOTS" value="true" />
    <option name="SCRIPT_NAME" value="ev3sim2d" />
    <option name="PARAMETERS" value={parameters} />
    <option name="MODULE_MODE" value="true" />
    <option name="EMULATE_TERMINAL" value="false" />
    <method v="2" />
  </configuration>
</component>
"""


def main(args) -> int:
    try:
        find_maze(args.world)
    except (WorldFileError, OSError) as err:
        return fail(f"--world {args.world}: {err}")
    folder = Path(args.folder)
    if not folder.is_dir():
        return fail(f"--folder {folder}: no such folder")
    try:
        if args.editor == "vscode":
            written = _vscode(make_folder_in(folder, ".vscode"), args.world)
        else:
            written = _pycharm(make_folder_in(folder, Path(".idea") / "runConfigurations"), args.world)
    except (JsoncError, OSError) as err:
        return fail(str(err))
    for line in written:
        print(line)
    return EXIT_OK


def _vscode(folder: Path, world: str) -> list[str]:
    plans = [
        (
            "tasks.json",
            lambda text, have: add_to_array(text, "tasks", _missing(vscode_tasks(), have, "tasks", "label")),
        ),
        (
            "launch.json",
            lambda text, have: add_to_array(
                text, "configurations", _missing(vscode_launches(), have, "configurations", "name")
            ),
        ),
        ("settings.json", lambda text, have: _settings(text, have, world)),
    ]
    planned = []  # every file is read and planned before any is written: a broken one stops them all
    for name, plan in plans:
        path = folder / name
        text = _read(path)
        try:
            have = parse(text)
        except JsoncError as err:
            raise JsoncError(
                f"{path}: {err}; fix it (or move it away) and run init again", err.line
            ) from None
        if type(have) is not dict:
            raise JsoncError(f"{path}: not an object ({{ ... }}); fix it and run init again", 1)
        planned.append((path, text, plan(text or NEW_FILES[name], have)))
    changes = []
    for path, text, new in planned:
        if text and new == text:
            changes.append(f"{path}: has what ev3sim2d needs already; left as it is")
            continue
        write_file(path, new)
        changes.append(f"{path}: {'added to' if text else 'written'}")
    changes.append(
        f'Open a program and press Ctrl+Shift+B (or F5, "{RUN_TASK}"); change the world in {folder / "settings.json"}.'
    )
    return changes


def _settings(text: str, have: dict, world: str) -> str:
    """The world, and the project's own debugger token (a new one, kept in the project: the launch
    configuration gives it to the run it attaches to)."""
    if TOKEN_SETTING not in have:
        text = add_key(text, TOKEN_SETTING, secrets.token_urlsafe(16))
    if WORLD_SETTING not in have:
        text = add_key(text, WORLD_SETTING, world)
    return text


def _pycharm(folder: Path, world: str) -> list[str]:
    path = folder / "run_in_ev3sim2d.xml"
    if path.exists() or path.is_symlink():
        return [f"{path}: there already; left as it is"]
    write_file(path, pycharm_configuration(world))
    return [f"{path}: written", f'Open a program and choose "{RUN_TASK}" in the run configurations.']


def _missing(ours: list[dict], have: dict, key: str, name: str) -> list[dict]:
    """Our entries whose name the file's list does not have yet (a student's entry of that name stays)."""
    names = {entry.get(name) for entry in have.get(key) or [] if isinstance(entry, dict)}
    return [entry for entry in ours if entry[name] not in names]


def _read(path: Path) -> str:
    """The settings file's text, read without following a link (a link, a FIFO or a device planted at the
    name is refused, PlantedFile), and not past MAX_BYTES."""
    try:
        data = read_limited(path, MAX_BYTES + 1)
    except FileNotFoundError:
        return ""
    if len(data) > MAX_BYTES:
        raise OSError(f"{path}: not an editor's settings file (over {MAX_BYTES // 2**20} MB)")
    try:
        return data.decode("utf-8-sig").replace("\r\n", "\n").replace("\r", "\n")  # (as read_text reads it)
    except UnicodeDecodeError as err:
        raise OSError(
            f"{path}: not UTF-8 text ({err.reason} at byte {err.start}); VS Code saves it as UTF-8"
        ) from None
