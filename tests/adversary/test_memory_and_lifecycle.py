"""A brick's processes together within its memory, a grading worker within its own, and nothing a
grader started outliving it, however it is ended.

A brick's memory limit is per process, and a brick may have 64 processes: four children held 1.8 GB
against a 512 MB limit.  Grading workers had no ceiling.  SIGTERM to the grader (`timeout`, a
cancelled CI job) left its workers, the zygote and a brick running for ever.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ev3sim2d.simulator import memory_watch
from tests.grading.lesson_maker import GOOD, write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]
needs_proc = pytest.mark.skipif(not memory_watch.available(), reason="needs /proc to see a brick's processes")

HOARDERS = """
import subprocess, sys, time
hoard = "import time\\nblock = bytearray({mb} * 2**20)\\nblock[::4096] = b'x' * len(block[::4096])\\ntime.sleep(30)\\n"
children = [subprocess.Popen([sys.executable, "-c", hoard.replace("30", "{hold}")]) for _ in range({count})]
for child in children:
    child.wait()  # (in real time: the children hold their memory meanwhile)
print("still here")
"""
SLOW = """
import subprocess, sys
subprocess.run([sys.executable, "-c", "import time; time.sleep(30)"])  # seconds of real time, in a child
"""


def run(program: Path, *args) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), *map(str, args)],
        capture_output=True, text=True, cwd=ROOT, timeout=180,
    )  # fmt: skip


@needs_proc
def test_children_that_together_pass_the_budget_end_the_run_for_memory(tmp_path):
    """Four children of 300 MB each (under the per-process limit, 1.2 GB together against the brick's
    1024 MB): the run ends for memory within moments, and none of them is left."""
    program = tmp_path / "hoard.py"
    program.write_text(HOARDERS.format(mb=300, count=4, hold=30))
    started = time.monotonic()
    done = run(program, "--time", "60", "--hang-after", "60", "--summary", tmp_path / "s.json")
    assert "ran out of memory" in done.stderr, done.stderr
    assert time.monotonic() - started < 30
    assert json.loads((tmp_path / "s.json").read_text())["output"] == []
    assert _processes_running("bytearray(300 * 2**20)") == []


@needs_proc
def test_children_within_the_budget_run_on(tmp_path):
    program = tmp_path / "modest.py"
    program.write_text(HOARDERS.format(mb=50, count=3, hold=1))
    done = run(program, "--time", "10", "--hang-after", "20", "--summary", tmp_path / "s.json")
    assert done.returncode == 0, done.stderr
    assert json.loads((tmp_path / "s.json").read_text())["output"] == ["still here"]


@pytest.mark.skipif(not hasattr(os, "fork"), reason="a forked worker's rlimit (Windows: a Job Object)")
@pytest.mark.needs_linux("memory_limit")  # (macOS refuses RLIMIT_AS: a worker has no ceiling there)
def test_every_grading_worker_has_a_memory_ceiling_of_its_own(tmp_path):
    """A lesson's own check runs in the worker: it reads the worker's address-space ceiling."""
    lesson = write_lesson(
        tmp_path / "lesson",
        lesson_text=(
            "title: Probe\ngoal: Any.\ntime_s: 1\nvariants:\n  - {name: room, world: room.yaml}\n"
            "checks:\n  - {name: probe, kind: probe, points: 1, goal: true}\n"
        ),
    )
    seen = tmp_path / "ceiling"
    (lesson / "check_probe.py").write_text(
        "import resource\nfrom ev3sim2d.grading.check import Check, Outcome\n\n"
        "class Probe(Check):\n    KIND = 'probe'\n    SUMMARY = 'reads the worker ceiling'\n"
        "    def evaluate(self, run):\n"
        f"        open({str(seen)!r}, 'w').write(str(resource.getrlimit(resource.RLIMIT_AS)[1]))\n"
        "        return Outcome(True, 'probed')\n"
    )
    program = write_program(tmp_path, "p.py", "pass\n")
    subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(program)], cwd=ROOT, timeout=120
    )
    import resource

    ceiling = int(seen.read_text())
    assert ceiling != resource.RLIM_INFINITY and ceiling < 64 * 2**30, ceiling


def _grader(tmp_path: Path, signal_name: str | None = None):
    """A class of slow honest programs being graded (2 at a time), ended by a signal mid-run."""
    lesson = write_lesson(tmp_path / "lesson", time_s=5)
    folder = tmp_path / "class"
    write_program(folder, "a_fast.py", GOOD)
    for n in range(4):
        write_program(folder, f"slow{n}.py", SLOW)
    return subprocess.Popen(
        [sys.executable, "-m", "ev3sim2d", "grade", str(lesson), str(folder), "--jobs", "2",
         "--json", str(tmp_path / "r.json"), "--junit", str(tmp_path / "r.xml")],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT,
        env={**os.environ, "EV3SIM2D_STATE_DIR": str(tmp_path / "state"), "TMPDIR": str(_temporary(tmp_path))},
    )  # fmt: skip


def _temporary(tmp_path: Path) -> Path:
    """The grader's temporary folder (its job folders, its bricks' scratch folders): the test's own."""
    folder = tmp_path / "tmp"
    folder.mkdir(exist_ok=True)
    return folder


@needs_proc
@pytest.mark.parametrize("name", ["SIGTERM", "SIGHUP", "SIGINT"])
def test_a_signal_ends_every_process_the_grader_started_and_keeps_what_was_done(tmp_path, name):
    grader = _grader(tmp_path)
    deadline = time.monotonic() + 120
    while not (tmp_path / "r.json").exists() or "a_fast" not in (tmp_path / "r.json").read_text():
        assert time.monotonic() < deadline and grader.poll() is None, "the first submission never finished"
        time.sleep(0.1)
    time.sleep(0.5)  # workers, the zygote and bricks of the slow ones are running now
    started = _descendants(grader.pid)
    assert len(started) >= 3, started
    grader.send_signal(getattr(signal, name))
    _, stderr = grader.communicate(timeout=60)
    assert grader.returncode == 128 + getattr(signal, name) if name != "SIGINT" else grader.returncode == 130
    assert "grading interrupted" in stderr
    done = json.loads((tmp_path / "r.json").read_text())["submissions"]
    assert [Path(s["submission"]).name for s in done][0] == "a_fast.py"
    assert 'name="' in (tmp_path / "r.xml").read_text()  # the JUnit report of what was done
    time.sleep(0.5)
    assert [pid for pid in started if _alive(pid)] == []
    assert list(_temporary(tmp_path).iterdir()) == [], "the grader left its job folders behind"


@needs_proc
def test_a_grader_killed_outright_takes_its_workers_zygote_and_bricks_with_it(tmp_path):
    grader = _grader(tmp_path)
    deadline = time.monotonic() + 120
    while len(_descendants(grader.pid)) < 4:
        assert time.monotonic() < deadline and grader.poll() is None
        time.sleep(0.1)
    started = _descendants(grader.pid)
    grader.kill()
    grader.wait()
    deadline = time.monotonic() + 5
    while [pid for pid in started if _alive(pid)] and time.monotonic() < deadline:
        time.sleep(0.1)
    assert [pid for pid in started if _alive(pid)] == []


def _descendants(pid: int) -> list[int]:
    children: dict[int, list[int]] = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat") as f:
                    parent = int(f.read().rsplit(")", 1)[1].split()[1])
            except (OSError, ValueError):
                continue
            children.setdefault(parent, []).append(int(name))
    found, stack = [], [pid]
    while stack:
        for child in children.get(stack.pop(), ()):
            found.append(child)
            stack.append(child)
    return found


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def _processes_running(marker: str) -> list[int]:
    found = []
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/cmdline", "rb") as f:
                    if marker.encode() in f.read():
                        found.append(int(name))
            except OSError:
                pass
    return found
