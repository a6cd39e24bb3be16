"""A classmate's world or robot file, and the live page's robot editor, as an attacker would write them.

Before: a 27 KB world of YAML anchors became 3000x3000 cells (gigabytes in `edit` and `live`), a 140 KB
tall world made `show` try to allocate 7 GiB, a 6 KB deeply nested file ended `run`, `show`, `edit` and
`live` in RecursionError, and a 1e12 cm wheel or 1e308 typed into the sensor editor aborted the physics.
Now each is refused where the file is read: exit code 2, the file:line and the limit in the message, in
bounded time and memory (the ceilings below; the memory is the command's own peak, where the system
tells it: `command`).
"""

from __future__ import annotations

import http.client
import json
import math
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from ev3sim2d.editor.page_guard import TOKEN_HEADER
from ev3sim2d.live.engine import LiveRun
from ev3sim2d.live.server import LiveServer, LiveWorldFile
from ev3sim2d.world.maze_file import load_maze

ROOT = Path(__file__).resolve().parents[2]
BASE_ROBOT = (ROOT / "ev3sim2d" / "robots" / "ev3-driving-base.yaml").read_text()
MEMORY_CEILING_KB = 150 * 1024
"""Peak resident memory of a command that refuses a file: about 47 MB is Python with ev3sim2d's
commands loaded (measured: `ev3sim2d show` of each bomb below peaks at 46-51 MB); before, the anchor
bomb took `edit` and `live` to 2.6-3.4 GB."""
TIME_CEILING_S = 20.0
"""Wall time of a refusal on a busy 2-core machine (each takes under a second alone)."""

PROGRAM = "print('hello')\n"


def within_memory(peak_kb: int | None) -> bool:
    """The command's peak under the ceiling; where the system tells no peak (no /proc), nothing to check."""
    if not os.path.exists("/proc/self/status"):
        return True
    return peak_kb is not None and peak_kb < MEMORY_CEILING_KB


# The command runs under a few lines that report its own peak resident memory as it exits: VmHWM, the
# high-water mark of the memory the program itself mapped.  (wait4's ru_maxrss will not do: Linux carries
# a process's peak over its exec, so a child of a large pytest process reports pytest's size.)
REPORTING = """
import atexit, runpy, sys
def peak():
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    sys.stderr.write("\\nPEAK_KB " + line.split()[1] + "\\n")
    except OSError:
        pass
atexit.register(peak)
sys.argv = ["ev3sim2d", *sys.argv[1:]]
runpy.run_module("ev3sim2d", run_name="__main__", alter_sys=True)
"""


def command(*args: str | Path, cwd: Path) -> tuple[int, str, float, int | None]:
    """`ev3sim2d ARGS` -> (exit code, stderr, seconds, peak resident KB of that process, None where the
    system does not say)."""
    started = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-c", REPORTING, *map(str, args)],
        cwd=cwd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        timeout=120,
    )  # fmt: skip
    seconds = time.monotonic() - started
    stderr, _, peak = done.stderr.rpartition("\nPEAK_KB ")
    if not _:
        return done.returncode, done.stderr, seconds, None
    return done.returncode, stderr, seconds, int(peak.split()[0])


# -- the hostile files ---------------------------------------------------------------------------------


def anchor_bomb() -> str:
    """27 KB: a 3000-cell row, aliased 2998 times, stands for a 3000x3000 grid."""
    wall, floor = "#" * 3000, "#" + "." * 2998 + "#"
    rows = "".join("  - *f\n" for _ in range(2997))
    return f'title: bomb\ngrid:\n  - &w "{wall}"\n  - &f "{floor}"\n{rows}  - *w\nstart: {{cell: [1, 1]}}\n'


def laughs_bomb() -> str:
    """A billion laughs: ten levels of ten aliases each, 10**10 cells' worth in 1 KB."""
    lines = ['a0: &a0 "##########"']
    for level in range(1, 11):
        lines.append(f"a{level}: &a{level} [{', '.join([f'*a{level - 1}'] * 10)}]")
    return "title: laughs\nlegend:\n  " + "\n  ".join(lines) + "\n"


def nesting_bomb() -> str:
    """6 KB of brackets nested 3000 deep."""
    return "title: " + "[" * 3000 + "]" * 3000 + "\n"


def tall_world() -> str:
    """140 KB: a grid 3 cells wide and 23,000 rows tall."""
    return "title: tall\ngrid: |\n  ###\n" + "  #.#\n" * 23_000 + "  ###\nstart: {cell: [1, 1]}\n"


def huge_world() -> str:
    """A valid small world padded with comments to 2 MB."""
    return "# padding\n" * 200_000 + "grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\n"


WORLDS = {
    "anchor bomb": (anchor_bomb, "aliases written out, is more than 1,000,000 characters"),
    "billion laughs": (laughs_bomb, "more than 100,000 values (aliases counted each time"),
    "nesting bomb": (nesting_bomb, "nested more than 32 deep"),
    "tall world": (tall_world, "at most 200 cells each way"),
    "huge world": (huge_world, "more than 1,000,000 bytes"),
}


def test_the_bombs_are_what_they_claim(tmp_path):
    """The files are as small as the attacks were (so the limits, not the sizes, stop them)."""
    assert len(anchor_bomb()) < 28_000 and len(laughs_bomb()) < 1_000 and len(nesting_bomb()) < 6_100
    assert len(tall_world()) < 140_000 and len(huge_world()) > 2_000_000


@pytest.mark.parametrize("name", list(WORLDS))
@pytest.mark.parametrize("front_door", ["run", "show", "edit", "live"])
def test_a_hostile_world_is_refused_by_every_command_quickly_and_in_little_memory(tmp_path, name, front_door):
    make, words = WORLDS[name]
    world = tmp_path / "world.yaml"
    world.write_text(make())
    (tmp_path / "prog.py").write_text(PROGRAM)
    args = {
        "run": ("run", "prog.py", "--maze", world),
        "show": ("show", world, "--png", tmp_path / "out.png"),
        "edit": ("edit", world),
        "live": ("live", "prog.py", "--maze", world),
    }[front_door]
    code, stderr, seconds, peak_kb = command(*args, cwd=tmp_path)
    assert code == 2, stderr
    assert "Traceback" not in stderr and "RecursionError" not in stderr, stderr
    assert f"{world}:" in stderr and words in stderr, stderr
    assert "docs/world-files.md" in stderr or "is this the right file" in stderr, stderr
    assert seconds < TIME_CEILING_S, seconds
    assert within_memory(peak_kb), f"{front_door} peaked at {peak_kb} KB"
    assert not (tmp_path / "out.png").exists()


EXTREME_ROBOTS = {
    "a 1e12 cm wheel": (("wheel_diameter_mm: 56", "wheel_diameter_mm: 1e12"), "must be 20 to 200 mm"),
    "a 1e-9 cm axle": (("axle_track_mm: 120", "axle_track_mm: 1.0e-8"), "must be 50 to 500 mm"),
    "an infinite axle": (("axle_track_mm: 120", "axle_track_mm: .inf"), "must be a number"),
    "a NaN body": (("front_cm: 9", "front_cm: .nan"), "must be a number"),
    "a 1e308 sensor radius": (("radius_cm: 7", "radius_cm: 1.0e+308"), "a sensor sits on the robot"),
    "a huge cone": (("cone_deg: 15", "cone_deg: 1.0e+300"), "must be 1 to 180 degrees"),
    "a huge angle": (("angle_deg: 180", "angle_deg: 1.0e+300"), "must be -360 to 360 degrees"),
    "huge noise": (("spot_cm: 1.5}", "spot_cm: 1.5, noise: 1.0e+300}"), "'noise' must be 0 to 100"),
    "a nesting bomb": (("name: ", "nested: " + "[" * 3000 + "]" * 3000 + "\nname: "), "nested more than 32"),
}


@pytest.mark.parametrize("name", list(EXTREME_ROBOTS))
@pytest.mark.parametrize("front_door", ["run", "show", "live"])
def test_a_robot_file_with_extreme_numbers_is_refused_with_the_range(tmp_path, name, front_door):
    (old, new), words = EXTREME_ROBOTS[name]
    assert old in BASE_ROBOT
    robot = tmp_path / "extreme.yaml"
    robot.write_text(BASE_ROBOT.replace(old, new, 1))
    (tmp_path / "prog.py").write_text(PROGRAM)
    args = {
        "run": ("run", "prog.py", "--robot", robot),
        "show": ("show", "line", "--robot", robot, "--png", tmp_path / "out.png"),
        "live": ("live", "prog.py", "--robot", robot),
    }[front_door]
    code, stderr, seconds, peak_kb = command(*args, cwd=tmp_path)
    assert code == 2, stderr
    assert "Traceback" not in stderr and f"{robot}:" in stderr and words in stderr, stderr
    assert seconds < TIME_CEILING_S and within_memory(peak_kb), peak_kb


# -- the live page's robot editor, over real HTTP ----------------------------------------------------------


@pytest.fixture
def live_page(tmp_path):
    """A live server on a paused run, and a function that posts to it as its page does."""
    program = tmp_path / "prog.py"
    program.write_text("import time\ntime.sleep(30)\n")
    world = tmp_path / "world.yaml"
    world.write_text("grid: |\n  ##########\n  #........#\n  #........#\n  #........#\n  ##########\n"
                     "start: {cell: [3, 2], heading_deg: 0}\n")  # fmt: skip
    live = LiveRun([program], load_maze(world))
    server = LiveServer(live, LiveWorldFile(world))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    live.start(paused=True)

    def request(method: str, path: str, body: bytes | None = None):
        conn = http.client.HTTPConnection("127.0.0.1", server.server_address[1], timeout=60)
        headers = {TOKEN_HEADER: server.token, "Content-Type": "application/json"}
        conn.request(method, path, body=body, headers=headers)
        response = conn.getresponse()
        raw = response.read()
        conn.close()
        return response.status, json.loads(raw) if raw else None

    deadline = time.monotonic() + 60
    while not request("GET", "/api/state")[1]["robots"] and time.monotonic() < deadline:
        time.sleep(0.05)
    yield request
    server.shutdown()
    server.server_close()
    live.close()


def test_the_robot_editor_refuses_extreme_numbers_and_the_run_goes_on(live_page):
    """1e308, 1e-300, NaN and infinity typed into the robot editor: each a 400 naming the key and the
    range; the live process stays up, its robot unchanged, and the run still steps."""
    status, robot = live_page("GET", "/api/robot?robot=1")
    assert status == 200
    good = robot["mapping"]
    color = next(i for i, s in enumerate(good["sensors"]) if s["kind"] == "color")
    attacks = [
        (("wheel_diameter_mm",), 1e308, "must be 20 to 200 mm"),
        (("axle_track_mm",), 1e-300, "must be 50 to 500 mm"),
        (("body", "width_cm"), 1e308, "must be 1 to 50 cm"),
        (("sensors", color, "radius_cm"), 1e308, "a sensor sits on the robot"),
        (("sensors", color, "angle_deg"), -1e308, "must be -360 to 360 degrees"),
        (("sensors", color, "spot_cm"), 1e308, "must be 0.1 to 10 cm"),
        (("sensors", color, "radius_cm"), math.nan, "must be a number"),
        (("sensors", color, "radius_cm"), math.inf, "must be a number"),
    ]
    for keys, value, words in attacks:
        mapping = json.loads(json.dumps(good))
        place = mapping
        for key in keys[:-1]:
            place = place[key]
        place[keys[-1]] = value
        body = json.dumps({"robot": 1, "mapping": mapping}).encode()  # NaN and Infinity as Python sends them
        status, answer = live_page("POST", "/api/robot", body)
        assert status == 400 and words in answer["error"], (keys, value, answer)
        assert answer["error"].startswith("the page's robot:")
    assert live_page("GET", "/api/robot?robot=1")[1]["mapping"] == good
    status, state = live_page("POST", "/api/step", json.dumps({"ms": 200}).encode())
    assert status == 200 and state["t_s"] == pytest.approx(0.2, abs=0.02)


def test_the_robot_editor_refuses_a_deeply_nested_robot_without_a_traceback(live_page):
    """A mapping nested 400 deep (JSON reads it; writing it out as YAML recursed past Python's limit), and
    a robot file's text nested 3000 deep: each a 400 saying it nests too deeply (the server's JSON reader
    or the robot file's reader, whichever meets it first)."""
    mapping = {"name": "x"}
    for _ in range(400):
        mapping = {"name": mapping}
    status, answer = live_page("POST", "/api/robot", json.dumps({"robot": 1, "mapping": mapping}).encode())
    assert status == 400 and (
        "nested more than 32 deep" in answer["error"] or "nests too deeply" in answer["error"]
    )
    text = "name: " + "[" * 3000 + "]" * 3000 + "\n"
    status, answer = live_page("POST", "/api/robot", json.dumps({"robot": 1, "text": text}).encode())
    assert status == 400 and "nested more than 32 deep" in answer["error"], answer
    assert live_page("GET", "/api/state")[0] == 200


@pytest.mark.parametrize("name", ["anchor bomb", "nesting bomb"])
def test_a_lesson_whose_world_is_a_bomb_is_refused_by_grade(tmp_path, name):
    """A lesson folder from elsewhere (a colleague's, a download) names a hostile world."""
    import shutil

    lesson = tmp_path / "wall-stop"
    shutil.copytree(ROOT / "lessons" / "wall-stop", lesson)
    make, words = WORLDS[name]
    (lesson / "room.yaml").write_text(make())
    code, stderr, seconds, peak_kb = command("grade", lesson, lesson / "solution.py", cwd=tmp_path)
    assert code == 2 and f"{lesson / 'room.yaml'}:" in stderr and words in stderr, stderr
    assert "Traceback" not in stderr and seconds < TIME_CEILING_S and within_memory(peak_kb)
