"""A Pybricks program's run is as deterministic as a python-ev3dev2 program's: the same program, world
and seed give the same fingerprint on two machines that differ as two machines do (hash seed, time
zone, the second of the wall clock; tests/test_determinism.py), whatever the program reads of them
through Pybricks or MicroPython's modules."""

from __future__ import annotations

import pytest

from tests.test_determinism import run_on_two_machines

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


@pytest.fixture(scope="module")
def summaries(tmp_path_factory) -> dict[str, list[dict]]:
    folder = tmp_path_factory.mktemp("pybricks-determinism")
    programs = {}
    for name, source in SOURCES.items():
        programs[name] = folder / name / "main.py"  # (a folder each: DataLog writes beside its program)
        programs[name].parent.mkdir()
        programs[name].write_text(PROGRAM.format(source=source))
    return run_on_two_machines(programs, folder)


@pytest.mark.parametrize("source", SOURCES)
def test_two_machines_give_the_same_pybricks_run(summaries, source):
    first, second = summaries[source]
    assert first["fingerprint"] and first["output"]
    assert (second["fingerprint"], second["output"]) == (first["fingerprint"], first["output"])
