"""Thonny plug-in: run the program open in the editor in ev3sim2d, in Thonny's shell.

Run → Run in ev3sim2d (and its toolbar button) saves the program and runs `ev3sim2d run PROGRAM --maze
WORLD` in Thonny's shell, through Thonny's own %Run of `launch.py` in the Python Thonny runs programs
with, so the run's output, its traceback (whose File "...", line N are links) and its one-line
`prog.py:12: error: ...` appear where the program's own would.  Run in ev3sim2d (live page) runs
`ev3sim2d live` instead: the robot drives in the browser.  ev3sim2d world… chooses the world, kept in
Thonny's options (ev3sim2d.world).  ev3sim2d itself must be installed in that Python (Tools → Manage
packages…); launch.py says so if it is not.
"""

from __future__ import annotations

import os

from thonny import get_runner, get_workbench

HERE = os.path.dirname(os.path.abspath(__file__))
LAUNCHER = os.path.join(HERE, "launch.py")
ICON = os.path.join(HERE, "run.png")
WORLD_OPTION = "ev3sim2d.world"
DEFAULT_WORLD = "line"


def run_in_ev3sim2d(command: str = "run") -> None:
    """Save the program open in the editor and run it in ev3sim2d (command: run, or live)."""
    path = _saved_program()
    if not path:
        return
    world = get_workbench().get_option(WORLD_OPTION) or DEFAULT_WORLD
    get_runner().execute_script(LAUNCHER, [command, path, "--maze", world], os.path.dirname(path))


def choose_world() -> None:
    """Ask for the world the programs run in: a shipped world's name or a world file's path."""
    from tkinter import simpledialog

    workbench = get_workbench()
    world = simpledialog.askstring(
        "ev3sim2d world",
        "A shipped world's name (empty, line, maze, colors, sumo, …) or a world file's path:",
        initialvalue=workbench.get_option(WORLD_OPTION) or DEFAULT_WORLD,
        parent=workbench,
    )
    if world and world.strip():
        workbench.set_option(WORLD_OPTION, world.strip())


def _saved_program() -> str | None:
    """The program open in the editor, saved first (None: no program, or the student cancelled)."""
    from thonny import editors

    save = (
        getattr(editors, "get_saved_current_script_path", None) or editors.get_saved_current_script_filename
    )
    return save()


def _can_run() -> bool:
    runner = get_runner()
    return bool(get_workbench().get_editor_notebook().get_current_editor()) and (
        runner is None or runner.is_waiting_toplevel_command()
    )


def load_plugin() -> None:
    workbench = get_workbench()
    workbench.set_default(WORLD_OPTION, DEFAULT_WORLD)
    workbench.add_command(
        "ev3sim2d_run",
        "run",
        "Run in ev3sim2d",
        run_in_ev3sim2d,
        tester=_can_run,
        group=11,
        image=ICON,
        caption="ev3sim2d",
        include_in_toolbar=True,
    )
    workbench.add_command(
        "ev3sim2d_live",
        "run",
        "Run in ev3sim2d (live page)",
        lambda: run_in_ev3sim2d("live"),
        tester=_can_run,
        group=11,
    )
    workbench.add_command("ev3sim2d_world", "run", "ev3sim2d world…", choose_world, group=11)
