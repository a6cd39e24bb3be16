"""A run of several bricks on cores of its own (simulator/cores.py) is the same run as any other, and gives
the simulator its cores back at its end."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from ev3sim2d.simulator import cores
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.needs_linux("affinity")
def test_several_bricks_on_cores_of_their_own_run_as_with_the_scheduler_s_choice(monkeypatch):
    world = load_maze(find_maze("line-shared"))
    programs = [ROOT / "examples" / "line_follower.py"] * 2
    before = os.sched_getaffinity(0)
    placed = []
    monkeypatch.setattr(cores, "machine_busy", lambda: False)
    started = cores.RunCores.brick_started
    monkeypatch.setattr(
        cores.RunCores,
        "brick_started",
        lambda self, i, pid: (placed.append(self.shared), started(self, i, pid)),
    )
    on_own = run_programs(programs, world, time_limit_s=3)
    assert placed == [True, True]
    assert os.sched_getaffinity(0) == before
    anywhere = run_programs(programs, world, time_limit_s=3, place=False)
    blocking = run_programs(programs, world, time_limit_s=3, spin=False)
    assert on_own.sim_time_s == 3.0
    fingerprints = {r.trace.fingerprint() for r in (on_own, anywhere, blocking)}
    assert len(fingerprints) == 1
