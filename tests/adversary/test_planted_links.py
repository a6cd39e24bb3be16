"""Whoever can write into a folder a writer of ev3sim2d writes in (a shared class folder, an unzipped
bundle, a classmate's project) can plant a link at any name it uses: nothing is written through one.

Each writer is played against links planted at every name it writes (its target, the target's `.bak`,
the folders it makes), pointing at a file of the victim's (their ~/.bashrc, here `victim`): the victim
is unchanged afterwards, and the writer either replaced the link by a regular file of its own or
refused with a message.  The grader's outputs have their own attacks in test_working_folder.py, and
what `ev3sim2d run` keeps of a program's files in tests/simulator/test_working_folder.py.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from ev3sim2d.editor.server import WorldFile
from ev3sim2d.live.engine import LiveRun
from ev3sim2d.live.server import LiveServer, LiveWorldFile, _cell, _save_robot, _save_world
from ev3sim2d.results.output_files import PlantedFile
from ev3sim2d.world.maze_file import load_maze
from ev3sim2d.world.source_error import WorldFileError

ROOT = Path(__file__).resolve().parents[2]
MAZE = ROOT / "mazes" / "empty.yaml"
pytestmark = pytest.mark.skipif(not hasattr(os, "symlink"), reason="no links here")
PRECIOUS = "export PATH=$HOME/bin:$PATH  # the victim's own\n"


@pytest.fixture
def victim(tmp_path) -> Path:
    path = tmp_path / "home" / ".bashrc"
    path.parent.mkdir()
    path.write_text(PRECIOUS)
    return path


@pytest.fixture
def shared(tmp_path) -> Path:
    """The shared folder, where the attacker may write."""
    folder = tmp_path / "class"
    folder.mkdir()
    return folder


def untouched(victim: Path) -> bool:
    return victim.read_text() == PRECIOUS and len(list(victim.parent.iterdir())) == 1


def test_the_editor_replaces_a_link_at_its_backup_and_refuses_one_at_the_world(shared, victim):
    """edit's save (editor/server.py WorldFile.save): the old text goes to WORLD.bak, then the new one to
    WORLD; a link at WORLD.bak is replaced, a link at WORLD is refused before anything is written."""
    world = shared / "world.yaml"
    shutil.copy(MAZE, world)
    (shared / "world.yaml.bak").symlink_to(victim)
    edited = WorldFile(world)
    shown = edited.world_json()
    data = {key: shown[key] for key in ("cell_cm", "cells", "regions", "starts")}
    data["cells"][1][1] = {**data["cells"][1][1], "wall": True, "char": None}
    edited.save(data)
    assert untouched(victim)
    assert (
        not (shared / "world.yaml.bak").is_symlink()
        and (shared / "world.yaml.bak").read_text() == MAZE.read_text()
    )
    planted = shared / "planted.yaml"
    planted.symlink_to(victim)
    with pytest.raises((PlantedFile, WorldFileError)):  # (it does not read as a world, or is not replaced)
        WorldFile(planted).save(data)
    assert untouched(victim) and planted.is_symlink()


@pytest.fixture
def live(shared):
    program = shared / "prog.py"
    program.write_text("import time\ntime.sleep(1)\n")
    world = shared / "arena.yaml"
    shutil.copy(MAZE, world)
    run = LiveRun([program], load_maze(world))
    server = LiveServer(run, LiveWorldFile(world))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    run.start(paused=True)
    yield server, world
    server.shutdown()
    server.server_close()
    run.close()


def test_live_saves_the_world_and_a_robot_never_through_a_link(live, shared, victim):
    """live's save-world and save-robot (live/server.py): links at the world's .bak, at a new robot file's
    name and at its .bak."""
    server, world = live
    (shared / "arena.yaml.bak").symlink_to(victim)
    _cell(server, {"col": 3, "row": 3, "wall": True})  # (a change, so that there is something to save)
    _save_world(server, {})
    assert untouched(victim) and not (shared / "arena.yaml.bak").is_symlink()
    (shared / "mine.yaml").symlink_to(victim)
    for replace in (False, True):  # refused as there already, then refused as not a regular file
        with pytest.raises(Exception) as refused:
            _save_robot(server, {"robot": 1, "file": "mine.yaml", "replace": replace})
        assert "mine.yaml" in str(refused.value)
    assert untouched(victim) and (shared / "mine.yaml").is_symlink()
    (shared / "other.yaml.bak").symlink_to(victim)
    _save_robot(server, {"robot": 1, "file": "other.yaml"})
    _save_robot(server, {"robot": 1})  # again, into its own file now: the old one to other.yaml.bak
    assert untouched(victim) and not (shared / "other.yaml.bak").is_symlink()
    assert (shared / "other.yaml").read_text().startswith(("#", "name"))


def test_a_runs_outputs_replace_links_planted_at_their_names(shared, victim):
    """ev3sim2d run --png --video --summary --trace --plot: each output is a new file renamed over its name."""
    program = shared / "prog.py"
    program.write_text(
        "from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C\nMoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)\n"
    )
    names = {
        "--png": "end.png",
        "--video": "run.mp4",
        "--summary": "run.json",
        "--trace": "run.npz",
        "--plot": "plot.png",
    }
    for name in names.values():
        (shared / name).symlink_to(victim)
    options = [part for option, name in names.items() for part in (option, name)]
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", "prog.py", "--maze", "empty", "--time", "2", *options, "--quiet"],
        cwd=shared, capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    if done.returncode != 0 and "matplotlib" in done.stderr:
        pytest.skip("no matplotlib for --plot")
    assert done.returncode == 0, done.stderr
    assert untouched(victim)
    for name in names.values():
        assert not (shared / name).is_symlink() and (shared / name).stat().st_size > 0
    assert json.loads((shared / "run.json").read_text())["fingerprint"]


@pytest.mark.parametrize(
    "editor, planted", [("vscode", ".vscode"), ("pycharm", ".idea"), ("vscode", ".vscode/tasks.json")]
)
def test_init_refuses_a_linked_folder_or_settings_file(shared, victim, editor, planted):
    """ev3sim2d init: a link at .vscode or .idea (to a folder of the victim's, e.g. their editor's own
    settings folder) would put the files there; a link at tasks.json would be read (a FIFO there would
    hang it).  Each is refused with a message, and nothing is written."""
    target = shared / planted
    target.parent.mkdir(parents=True, exist_ok=True)
    target.symlink_to(victim.parent if "." in planted and "/" not in planted else victim)
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "init", editor, "--folder", str(shared)],
        capture_output=True, text=True, timeout=120,
    )  # fmt: skip
    assert done.returncode != 0 and "refused" in done.stderr, done.stderr
    assert untouched(victim)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no FIFOs here")
def test_init_does_not_hang_on_a_fifo_planted_as_a_settings_file(shared):
    (shared / ".vscode").mkdir()
    os.mkfifo(shared / ".vscode" / "settings.json")
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "init", "vscode", "--folder", str(shared)],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert done.returncode != 0 and "settings.json" in done.stderr
