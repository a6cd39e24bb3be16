#!/usr/bin/env python3
"""How much faster than real time ev3sim2d runs, measured in one run on this machine.

(a) the world alone: one robot driving an arc in mazes/line.yaml, its four
    sensors read every tick (no program, no scheduler);
(b) a busy-loop proportional line follower written against the ev3dev2 shim
    (examples/line_follower.py) in mazes/line.yaml: program, scheduler and world.

Targets: (b) at least 300x real time, and at least half as fast as (a).
Run:  python benchmarks/realtime.py [--seconds 60] [--repeat 3]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

from ev3sim2d.run import run_programs
from ev3sim2d.simulation import Simulation
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[1]


def world_alone(world, seconds: float) -> float:
    """Real-time factor of the world stepping one robot and reading its four sensors every tick."""
    sim = Simulation(world, [("robot", world.robot, world.start)])
    robot = sim.robots[0]
    for motor, speed in ((robot.left, "240"), (robot.right, "300")):  # a left arc that stays clear of walls
        motor.write("speed_sp", speed)
        motor.write("command", "run-forever")
    sensors = list(robot.sensors.values())
    ticks = int(round(seconds * 1e6 / sim.tick_us))
    start = time.perf_counter()
    now = 0
    for _ in range(ticks):
        now += sim.tick_us
        sim.tick(now)
        for sensor in sensors:
            sensor.values()
    return seconds / (time.perf_counter() - start)


def line_follower(world, seconds: float) -> float:
    """Real-time factor of the shim line follower (simulation wall time, not interpreter start-up)."""
    result = run_programs([ROOT / "examples" / "line_follower.py"], world, time_limit_s=seconds)
    assert result.status == "time_limit", result.reason
    return result.sim_time_s / result.wall_time_s


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated seconds per measurement")
    parser.add_argument("--repeat", type=int, default=3, help="measurements of each; the best is reported")
    args = parser.parse_args()
    world = load_maze(find_maze("line"))
    a = max(world_alone(world, args.seconds) for _ in range(args.repeat))
    b = max(line_follower(world, args.seconds) for _ in range(args.repeat))
    print(f"(a) world alone, 4 sensors read every tick: {a:7.0f}x real time")
    print(f"(b) busy-loop line follower via the shim:    {b:7.0f}x real time")
    print(f"(b)/(a) = {b / a:.2f}   targets: (b) >= 300x, (b)/(a) >= 0.50")
    print("(best of each; the figures move with what else the shared machine is running)")


if __name__ == "__main__":
    main()
