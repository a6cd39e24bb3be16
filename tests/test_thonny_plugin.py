"""The Thonny plug-in (thonny-ev3sim2d/): loaded against a stand-in of Thonny's workbench, as Thonny loads
a plug-in (thonnycontrib.*.load_plugin), it adds its commands and runs the right one in Thonny's shell.

What stands in for Thonny is what the plug-in uses of it, with Thonny 4's names: workbench.add_command
(thonny/workbench.py), get_option/set_default/set_option, the editor notebook's current editor,
thonny.editors.get_saved_current_script_path, and runner.execute_script(script, args, working_directory),
which types `%Run script args` into the shell.
"""

from __future__ import annotations

import importlib
import os
import shutil
import subprocess
import sys
import types
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PLUGIN = ROOT / "thonny-ev3sim2d"


class Workbench:
    def __init__(self, program: Path | None):
        self.commands: dict[str, dict] = {}
        self.options: dict[str, object] = {}
        self.program = program

    def add_command(self, command_id, menu_name, command_label, handler=None, **options):
        self.commands[command_id] = {"menu": menu_name, "label": command_label, "handler": handler, **options}

    def set_default(self, name, value):
        self.options.setdefault(name, value)

    def get_option(self, name, default=None):
        return self.options.get(name, default)

    def set_option(self, name, value):
        self.options[name] = value

    def get_editor_notebook(self):
        return types.SimpleNamespace(get_current_editor=lambda: self.program and object())


class Runner:
    def __init__(self):
        self.scripts: list[tuple] = []

    def execute_script(self, script_path, args, working_directory, command_name="Run"):
        self.scripts.append((script_path, list(args), working_directory))

    def is_waiting_toplevel_command(self):
        return True


@pytest.fixture
def thonny(monkeypatch, tmp_path):
    """A stand-in `thonny` package, and the plug-in imported from the repository as Thonny finds it."""
    program = tmp_path / "my robot" / "prog.py"
    program.parent.mkdir()
    program.write_text("import time\ntime.sleep(0.5)\nprint(1 / 0)\n")
    workbench, runner = Workbench(program), Runner()
    saved = []
    stand_in = types.ModuleType("thonny")
    stand_in.get_workbench = lambda: workbench
    stand_in.get_runner = lambda: runner
    editors = types.ModuleType("thonny.editors")
    editors.get_saved_current_script_path = lambda: saved.append(program) or str(program)
    stand_in.editors = editors
    monkeypatch.setitem(sys.modules, "thonny", stand_in)
    monkeypatch.setitem(sys.modules, "thonny.editors", editors)
    monkeypatch.syspath_prepend(str(PLUGIN))
    for name in [n for n in sys.modules if n.startswith("thonnycontrib")]:
        monkeypatch.delitem(sys.modules, name)
    plugin = importlib.import_module("thonnycontrib.ev3sim2d")
    plugin.load_plugin()
    return types.SimpleNamespace(
        plugin=plugin, workbench=workbench, runner=runner, program=program, saved=saved
    )


def test_the_plugin_adds_a_toolbar_button_and_the_run_menus_commands(thonny):
    commands = thonny.workbench.commands
    assert set(commands) == {"ev3sim2d_run", "ev3sim2d_live", "ev3sim2d_world"}
    run = commands["ev3sim2d_run"]
    assert (run["menu"], run["label"], run["include_in_toolbar"]) == ("run", "Run in ev3sim2d", True)
    assert os.path.isabs(run["image"]) and Path(run["image"]).is_file()  # (Thonny takes an absolute path)
    assert run["tester"]() is True
    assert thonny.workbench.get_option("ev3sim2d.world") == "line"


def test_run_saves_the_program_and_runs_ev3sim2d_on_it_in_the_shell(thonny):
    thonny.workbench.commands["ev3sim2d_run"]["handler"]()
    assert thonny.saved == [thonny.program]
    [(script, args, folder)] = thonny.runner.scripts
    assert script == thonny.plugin.LAUNCHER and Path(script).is_file()
    assert args == ["run", str(thonny.program), "--maze", "line"] and folder == str(thonny.program.parent)


def test_the_live_command_and_the_chosen_world(thonny):
    thonny.workbench.set_option("ev3sim2d.world", "maze")
    thonny.workbench.commands["ev3sim2d_live"]["handler"]()
    assert thonny.runner.scripts[-1][1] == ["live", str(thonny.program), "--maze", "maze"]


def test_what_the_shell_runs_is_an_ev3sim2d_run_of_the_program(thonny):
    """The launcher, run as Thonny's %Run runs it (the program's folder as the working folder), is
    `ev3sim2d run`: its output, the traceback with the program's lines, and the editor line."""
    thonny.workbench.commands["ev3sim2d_run"]["handler"]()
    [(script, args, folder)] = thonny.runner.scripts
    done = subprocess.run(
        [sys.executable, script, *args[:2], "--maze", "empty"],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 1
    assert f'File "{thonny.program}", line 3' in done.stderr
    assert f"{thonny.program}:3: error: ZeroDivisionError: division by zero" in done.stderr


def test_without_ev3sim2d_the_launcher_says_how_to_install_it(tmp_path):
    done = subprocess.run(
        [sys.executable, "-S", "-I", str(PLUGIN / "thonnycontrib" / "ev3sim2d" / "launch.py"), "run", "x.py"],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert done.returncode == 2 and "Tools → Manage packages" in done.stderr


def test_the_plugin_is_a_package_pip_builds(tmp_path):
    """(from a copy, as tests/installed builds ev3sim2d's: an in-tree build would leave build/ behind)"""
    source = tmp_path / "thonny-ev3sim2d"
    shutil.copytree(PLUGIN, source, ignore=shutil.ignore_patterns("__pycache__", "build", "*.egg-info"))
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "-q", "--no-deps", "-w", str(tmp_path / "dist"), str(source)],
        check=True, capture_output=True, timeout=300,
    )  # fmt: skip
    [wheel] = (tmp_path / "dist").glob("thonny_ev3sim2d-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    assert {"thonnycontrib/ev3sim2d/__init__.py", "thonnycontrib/ev3sim2d/launch.py"} <= set(names)
    assert "thonnycontrib/ev3sim2d/run.png" in names
    assert "thonnycontrib/__init__.py" not in names  # (a namespace package, shared with every plug-in)
