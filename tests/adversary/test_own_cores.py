"""A brick's core, as a determined student would fight it: a run of several bricks gives the simulator a core
of its own and the bricks the others (simulator/cores.py).  A program may move itself (and what it forks)
onto the simulator's core, or onto every core, and spin there: that changes how fast the run goes, never
what happens in it, for itself or for the robot beside it."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from ev3sim2d.simulator import cores
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[2]

HOG = textwrap.dedent(
    """
    import os
    from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
    from ev3dev2.sensor import INPUT_3
    from ev3dev2.sensor.lego import ColorSensor
    moved = []
    for cores in ({0}, set(range(os.cpu_count() or 1))):  # the simulator's core, then every core
        try:
            os.sched_setaffinity(0, cores)
            moved.append(sorted(os.sched_getaffinity(0)))
        except (AttributeError, OSError, ValueError):  # (refused by the sandbox, or no such call)
            moved.append(None)
    print("moved", moved)
    if hasattr(os, "fork"):
        try:
            if os.fork() == 0:  # a child that spins on the simulator's core for ever
                try:
                    os.sched_setaffinity(0, {0})
                except (AttributeError, OSError):
                    pass
                while True:
                    pass
        except OSError:
            pass
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    eye = ColorSensor(INPUT_3)
    while True:
        light = eye.reflected_light_intensity
        tank.on(20 + light // 10, 20)
    """
)


@pytest.mark.needs_linux("affinity")
def test_a_brick_on_the_simulators_core_changes_the_speed_never_the_run(tmp_path, monkeypatch):
    monkeypatch.setattr(cores, "machine_busy", lambda: False)  # (the run places its processes)
    hog = tmp_path / "hog.py"
    hog.write_text(HOG)
    world = load_maze(find_maze("line-shared"))
    programs = [hog, ROOT / "examples" / "line_follower.py"]
    runs = [
        run_programs(programs, world, time_limit_s=4),
        run_programs(programs, world, time_limit_s=4, place=False),
        run_programs(programs, world, time_limit_s=4, spin=False),
    ]
    for run in runs:
        assert run.sim_time_s == 4.0 and run.error is None, run.error
    assert len({run.trace.fingerprint() for run in runs}) == 1
    said = [line.text for line in runs[0].trace.output if line.robot == 0]
    assert said and said[0].startswith("moved"), said
    assert said[0].startswith(("moved [[0], ", "moved [None, ")), (
        said
    )  # (it sat on the simulator's core, if let)
    # the honest robot beside it drives as it does beside a robot that only follows the line
    honest = run_programs([ROOT / "examples" / "line_follower.py"] * 2, world, time_limit_s=4)
    mine = runs[0].trace.motion()[:, runs[0].trace.robot_columns(1)]
    alone = honest.trace.motion()[:, honest.trace.robot_columns(1)]
    assert (mine == alone).all()
