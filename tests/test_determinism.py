"""The same program, world and seed give the same run, whatever the program asks of the machine.

The README promises that a run's fingerprint is the same on any machine.  Each program below
steers the robot (and prints) with a value from one source that differs between two machines, or
two runs on one: random numbers seeded from the system, numpy's generators without a seed, string
hashes, the wall clock and the time zone.  Each is run twice with `ev3sim2d run PROG --maze empty
--time 5 --summary s.json`, from environments that differ as two machines' do (PYTHONHASHSEED
`random` and `123`, the time zone, another second of the wall clock), and both summaries must
have the same fingerprint.  Where the simulator does not pin a source down, the runs differ.
"""

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
    "random_seeded_by_the_system": "import random\nrandom.seed()\nvalue = random.random()",
    "random_without_seeding": "import random\nvalue = random.random()",
    "numpy_legacy_random": "import numpy\nvalue = float(numpy.random.random())",
    "numpy_default_rng_without_seed": "import numpy\nvalue = float(numpy.random.default_rng().random())",
    "hash_of_a_string": 'value = hash("some string") % 1000 / 1000',
    "order_of_a_set_of_strings": (
        'words = ["alpha", "beta", "gamma", "delta", "echo", "foxtrot", "golf", "hotel"]\n'
        "value = sum(i * words.index(w) for i, w in enumerate(set(words))) % 97 / 97"
    ),
    "order_of_a_set_of_the_programs_objects": (
        "class Node:\n    def __init__(self, n):\n        self.n = n\n"
        "nodes = set(Node(i) for i in range(60))\n"
        "value = sum(i * node.n for i, node in enumerate(nodes)) % 97 / 97"
    ),
    "repr_of_an_object": "class Thing:\n    pass\nvalue = int(repr(Thing()).split()[-1][:-1], 16) % 97 / 97",
    "time_time": "import time\nvalue = time.time() % 1",
    "time_localtime": "import time\nt = time.localtime()\nvalue = (t.tm_hour * 3600 + t.tm_min * 60 + t.tm_sec) / 86400",
    "time_strftime": 'import time\nvalue = int(time.strftime("%H%M%S")) / 240000',
    "datetime_now": "from datetime import datetime\nnow = datetime.now()\nvalue = (now.hour * 3600 + now.minute * 60 + now.second) / 86400",
    "datetime_fromtimestamp": (
        "import time\nfrom datetime import datetime\nnow = datetime.fromtimestamp(time.time())\nvalue = now.hour / 24"
    ),
}

PROGRAM = """\
{source}
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

print("value", value)
MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(SpeedPercent(20 + 40 * value), SpeedPercent(20), 1)
"""

# two machines: another hash seed, another time zone (and the second run starts in another second)
MACHINES = ({"PYTHONHASHSEED": "random", "TZ": "UTC"}, {"PYTHONHASHSEED": "123", "TZ": "Asia/Kolkata"})


def _run(program: Path, machine: dict, summary: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONHASHSEED", "TZ")}
    env.update(machine)
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--maze", "empty", "--time", "5"]
        + ["--summary", str(summary), "--quiet"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(summary.read_text())


def run_on_two_machines(programs: dict[str, Path], folder: Path) -> dict[str, list[dict]]:
    """Every program run on the first machine, then (in a later second of the wall clock) on the second:
    name -> [its summary on each]."""
    found: dict[str, list[dict]] = {name: [] for name in programs}
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


@pytest.fixture(scope="module")
def summaries(tmp_path_factory) -> dict[str, list[dict]]:
    folder = tmp_path_factory.mktemp("determinism")
    programs = {}
    for name, source in SOURCES.items():
        programs[name] = folder / f"{name}.py"
        programs[name].write_text(PROGRAM.format(source=source))
    return run_on_two_machines(programs, folder)


@pytest.mark.parametrize("source", SOURCES)
def test_two_machines_give_the_same_run(summaries, source):
    first, second = summaries[source]
    assert (second["fingerprint"], second["output"]) == (first["fingerprint"], first["output"])
