"""A Pybricks program's run is as deterministic as a python-ev3dev2 program's: the same program, world
and seed give the same fingerprint on two machines that differ as two machines do (hash seed, time
zone, the second of the wall clock; tests/test_determinism.py), whatever the program reads of them
through Pybricks or MicroPython's modules."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

# each source sets `value`, a number in [0, 1) that steers the robot
SOURCES = {
    "urandom_without_seeding": "import urandom\nvalue = urandom.random()",
    "urandom_randint": "import urandom\nvalue = urandom.randint(0, 99) / 100",
    "utime_ticks_ms": "import utime\nvalue = utime.ticks_ms() % 1000 / 1000",
    "utime_localtime": "import utime\nt = utime.localtime()\nvalue = (t[3] * 3600 + t[4] * 60 + t[5]) / 86400",
    "stopwatch": "from pybricks.tools import StopWatch, wait\nw = StopWatch()\nwait(123)\nvalue = w.time() / 1000",
    "datalog_file_name": (
        "import os\nfrom pybricks.tools import DataLog\nlog = DataLog('a', name='run')\n"
        "value = int(log.file.name.split('_')[-1].split('.')[0]) % 1000 / 1000"
    ),
}

PROGRAM = """\
#!/usr/bin/env pybricks-micropython
{source}
from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.robotics import DriveBase

print("value", value)
robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=56, axle_track=120)
robot.drive(100, 90 * value)
from pybricks.tools import wait
wait(1500)
robot.turn(int(90 * value))
"""

MACHINES = ({"PYTHONHASHSEED": "random", "TZ": "UTC"}, {"PYTHONHASHSEED": "123", "TZ": "Asia/Kolkata"})


def _run(program: Path, machine: dict, summary: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHASHSEED", "TZ")}
    env.update(machine)
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--maze", "empty", "--time", "5"]
        + ["--summary", str(summary), "--quiet"],
        capture_output=True, text=True, env=env, timeout=120,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    return json.loads(summary.read_text())


@pytest.fixture(scope="module")
def summaries(tmp_path_factory) -> dict[str, list[dict]]:
    folder = tmp_path_factory.mktemp("pybricks-determinism")
    programs = {}
    for name, source in SOURCES.items():
        programs[name] = folder / name / "main.py"  # (a folder each: DataLog writes beside its program)
        programs[name].parent.mkdir()
        programs[name].write_text(PROGRAM.format(source=source))
    found: dict[str, list[dict]] = {name: [] for name in SOURCES}
    with ThreadPoolExecutor(max_workers=2) as pool:
        for i, machine in enumerate(MACHINES):
            if i:
                time.sleep(1.05 - time.time() % 1)  # the wall clock shows another second
            runs = {
                name: pool.submit(_run, path, machine, folder / f"{name}-{i}.json")
                for name, path in programs.items()
            }
            for name, run in runs.items():
                found[name].append(run.result())
    return found


@pytest.mark.parametrize("source", SOURCES)
def test_two_machines_give_the_same_pybricks_run(summaries, source):
    first, second = summaries[source]
    assert first["fingerprint"] and first["output"]
    assert (second["fingerprint"], second["output"]) == (first["fingerprint"], first["output"])
