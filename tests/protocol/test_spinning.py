"""When the simulator and its bricks spin as they wait for each other (protocol/stream.cores_idle), and on
which cores a run with several bricks puts them (simulator/cores.py): neither changes what a run does."""

from __future__ import annotations

import contextlib
import io
import os
import signal
import subprocess
import sys
import time

import pytest

from ev3sim2d.protocol import stream
from ev3sim2d.simulator import cores
from ev3sim2d.simulator.cores import RunCores


@pytest.fixture
def machine(monkeypatch):
    """A 2-core machine whose /proc/loadavg says `running[0]` processes run (set by the test)."""
    running = [2]

    def fake_open(path, mode="r", *args, **kwargs):
        assert path == "/proc/loadavg"
        return io.BytesIO(f"0.50 0.40 0.30 {running[0]}/300 12345\n".encode())

    monkeypatch.setattr(stream, "open", fake_open, raising=False)
    monkeypatch.setattr(stream, "_CORES", 2)
    monkeypatch.setattr(stream, "LOAD_CHECK_S", -1.0)  # a fresh look at every call
    stream.spinning_processes(2, False)
    yield running
    stream.spinning_processes(2, False)


def test_a_moment_s_crowd_does_not_stop_the_spinning_two_looks_of_three_do(machine):
    assert stream.cores_idle()
    machine[0] = 3  # a brick starting, a kernel thread: one look
    assert stream.cores_idle()
    machine[0] = 2
    assert stream.cores_idle() and stream.cores_idle()
    machine[0] = 4  # another program that keeps running
    assert stream.cores_idle()  # (one crowded look of the last three)
    assert not stream.cores_idle()
    machine[0] = 2
    assert not stream.cores_idle()  # two of the last three still crowded
    assert stream.cores_idle()


def test_more_spinning_processes_than_cores_spin_only_on_cores_of_their_own(machine):
    machine[0] = 5  # the simulator and four bricks, all running
    stream.spinning_processes(5, False)
    assert not stream.cores_idle()  # they would share cores by the scheduler's time slices
    stream.spinning_processes(5, True)
    assert stream.cores_idle() and stream.cores_idle()  # theirs: five running are their own
    machine[0] = 6  # and a thread of theirs beside them (the memory watch's)
    assert all(stream.cores_idle() for _ in range(5))
    machine[0] = 7  # and another program: only when every one of the last three looks finds it
    assert stream.cores_idle() and stream.cores_idle()
    assert not stream.cores_idle()
    machine[0] = 5
    assert stream.cores_idle()


def _affinity_of(pid: int) -> set[int]:
    return os.sched_getaffinity(pid)


@pytest.mark.needs_linux("affinity")
def test_several_bricks_get_the_cores_the_simulator_does_not_keep(monkeypatch):
    monkeypatch.setattr(cores, "machine_busy", lambda: False)  # (whatever else this machine runs now)
    allowed = sorted(os.sched_getaffinity(0))
    share = RunCores(3, spin=True)
    assert share.shared
    sleepers = [subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"]) for _ in range(3)]
    try:
        for i, p in enumerate(sleepers):
            share.brick_started(i, p.pid)
        share.start()
        assert _affinity_of(0) == {allowed[0]}
        theirs = allowed[1:]
        assert [_affinity_of(p.pid) for p in sleepers] == [{theirs[i % len(theirs)]} for i in range(3)]
        share.end()
        assert _affinity_of(0) == set(allowed)
        assert stream._load["ours"] == 2 and not stream._load["own_cores"]
    finally:
        for p in sleepers:
            p.kill()
            p.wait()


@pytest.mark.needs_linux("affinity", "proc", "fork")
def test_a_process_a_brick_forked_before_it_was_placed_joins_it_as_the_run_begins(monkeypatch, tmp_path):
    """A brick is the process started and the sandboxed one it forks to run the program: one forked before
    its parent was placed would run anywhere, so the run places each brick's whole tree as it begins."""
    monkeypatch.setattr(cores, "machine_busy", lambda: False)
    allowed = sorted(os.sched_getaffinity(0))
    ready = tmp_path / "child"
    forks = (
        "import os, sys, time\n"
        "if os.fork() == 0:\n"
        f"    open({str(ready)!r}, 'w').write(str(os.getpid())); time.sleep(30)\n"
        "time.sleep(30)\n"
    )
    bricks = [
        subprocess.Popen([sys.executable, "-c", forks]),
        subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"]),
    ]
    child = None
    try:
        for _ in range(500):
            if ready.exists() and ready.read_text():
                break
            time.sleep(0.01)
        child = int(ready.read_text())
        share = RunCores(2, spin=True)
        for i, p in enumerate(bricks):
            share.brick_started(i, p.pid)
        assert _affinity_of(child) == set(allowed)  # (forked before: not placed with its parent)
        share.start()
        assert _affinity_of(child) == _affinity_of(bricks[0].pid) == {allowed[1]}
        share.end()
    finally:
        for p in bricks:
            p.kill()
            p.wait()
        if child is not None:
            with contextlib.suppress(OSError):
                os.kill(child, signal.SIGKILL)


@pytest.mark.needs_linux("affinity")
def test_one_brick_a_run_that_may_not_spin_or_place_or_a_busy_machine_keep_the_scheduler_s_choice(
    monkeypatch,
):
    allowed = os.sched_getaffinity(0)
    sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)"])
    try:
        monkeypatch.setattr(cores, "machine_busy", lambda: False)
        shares = [RunCores(1, spin=True), RunCores(4, spin=False), RunCores(4, spin=True, place=False)]
        monkeypatch.setattr(cores, "machine_busy", lambda: True)
        shares.append(RunCores(4, spin=True))
        for share in shares:
            share.brick_started(0, sleeper.pid)
            share.start()
            assert not share.shared
            assert _affinity_of(0) == allowed and _affinity_of(sleeper.pid) == allowed
            share.end()
    finally:
        sleeper.kill()
        sleeper.wait()


def test_without_the_affinity_calls_nothing_is_placed_and_so_many_do_not_spin(monkeypatch):
    """Windows and macOS: no os.sched_setaffinity.  Four bricks on two cores then block as they wait."""
    monkeypatch.delattr(os, "sched_setaffinity", raising=False)
    monkeypatch.setattr(stream, "_CORES", 2)
    share = RunCores(4, spin=True)
    share.brick_started(0, os.getpid())
    share.start()
    assert not share.shared and not stream.cores_idle()
    share.end()
    assert stream._load["ours"] == 2
