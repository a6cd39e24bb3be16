"""A Pybricks program goes through every front door as a python-ev3dev2 one does: the Python API, the
debugger, `live` and `serve`/`join` run it in the same brick, with the same devices and the same
fingerprints."""

from __future__ import annotations

import json
import math
import re
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

from ev3sim2d import World, simulate
from tests.test_serve_join import Served, _command, _env, _join

STRAIGHT_500 = """\
#!/usr/bin/env pybricks-micropython
from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
robot.straight(500)
print("there", robot.distance())
"""

DEBUGGED = """\
from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase
from pybricks.tools import wait

robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
robot.drive(100, 0)
wait(1000)
breakpoint()
robot.straight(200)
print("distance", robot.distance())
"""

OPEN = """
    ##########
    #........#
    #........#
    #........#
    ##########
"""


def test_the_python_api_runs_a_pybricks_program_that_drives_50_cm():
    world = World.from_text(OPEN, cell_cm=20, starts=[(2, 2, 0)], name="open")
    result = simulate(STRAIGHT_500, world=world, time_s=10)
    assert result.status == "finished"
    start, end = result.poses[0], result.poses[-1]
    assert math.isclose(end[0] - start[0], 50, abs_tol=0.1) and abs(end[1] - start[1]) < 0.1
    assert [line.text for line in result.output] == ["there 500"]


def _run(folder: Path, *options: str, commands: str = "") -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", "prog.py", "--maze", "empty", "--time", "5", *options],
        input=commands, capture_output=True, text=True, cwd=folder, timeout=120,
    )  # fmt: skip


def _fingerprint(path: Path) -> str:
    return json.loads(path.read_text())["fingerprint"]


def test_the_debugger_stops_a_pybricks_program_and_looking_changes_nothing(tmp_path):
    (tmp_path / "prog.py").write_text(DEBUGGED)
    done = _run(tmp_path, "--summary", "debugged.json", commands="p robot.distance()\nw\nc\n")
    assert done.returncode == 0, done.stderr
    assert "ev3sim2d: stopped at prog.py:10 in <module> (thread MainThread, at 1.0" in done.stdout
    looked = int(done.stdout.split("(ev3sim2d) ")[1].split("\n")[0])
    assert 80 < looked < 100  # 1 s at 100 mm/s, less the start's ramp
    plain = _run(tmp_path, "--summary", "plain.json")
    assert plain.returncode == 0, plain.stderr
    assert _fingerprint(tmp_path / "debugged.json") == _fingerprint(tmp_path / "plain.json")


def test_live_runs_a_pybricks_program_to_its_end(tmp_path):
    (tmp_path / "prog.py").write_text(STRAIGHT_500)
    process = subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "live", "prog.py", "--no-browser", "--max-speed", "--time", "10"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp_path,
    )  # fmt: skip
    try:
        url = None
        while url is None:
            line = process.stdout.readline()
            assert line, "live ended before it gave its address"
            found = re.search(r"at (http://127\.0\.0\.1:\d+/)#token=([A-Za-z0-9_-]+)", line)
            url, token = (found.group(1), found.group(2)) if found else (None, None)
        deadline = time.monotonic() + 60
        while True:
            request = urllib.request.Request(url + "api/state", headers={"X-Ev3sim2d-Token": token})
            with urllib.request.urlopen(request, timeout=30) as answer:
                state = json.loads(answer.read())
            if state.get("status") == "ended":
                break
            assert time.monotonic() < deadline, state.get("status")
            time.sleep(0.1)
        assert [p["text"] for p in state["printed"]] == ["there 500"] and state["error"] is None
        assert 4.0 < state["t_s"] < 4.5  # 500 mm at the default settings: 4.2 s on the firmware's trapezoid
    finally:
        process.kill()
        process.wait()


def test_a_joined_pybricks_program_runs_as_the_same_program_run_at_once(tmp_path):
    program = tmp_path / "straight.py"
    program.write_text(STRAIGHT_500)
    subprocess.run(
        _command("run", str(program), "--maze", "empty", "--time", "6", "--quiet", "--summary", "run.json"),
        cwd=tmp_path, env=_env(), check=True, capture_output=True,
    )  # fmt: skip
    served = Served(tmp_path, "--maze", "empty", "--robots", "1", "--time", "6", "--summary", "served.json")
    try:
        joined = _join(served.address, program, "--name", "ada", cwd=tmp_path)
        out, err = joined.communicate(timeout=120)
        assert served.finish() == 0, served.log()
        assert joined.returncode == 0, err
        assert "there 500" in out
        assert _fingerprint(tmp_path / "served.json") == _fingerprint(tmp_path / "run.json")
    finally:
        served.stop()
