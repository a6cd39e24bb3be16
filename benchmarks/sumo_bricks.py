#!/usr/bin/env python3
"""Several robots with their bricks, against the world alone, in one run (issue 28).

Rows: 1, 2 and 4 robots in mazes/sumo-4.yaml.
- world alone: the robots' motors running, each robot's sensors read every tick (no brick);
- sumo: each robot runs examples/sumo.py (busy: it reads two sensors and writes its motors each
  time round), in its sandboxed brick;
- moves: each robot runs a program of blocking moves (on_for_seconds, on_for_degrees, sleep), which
  waits for its motors most of the time: what "nothing from me before t" saves.
Ratios to the world alone of the same row.  EV3SIM2D_EVERY_TICK=1 forces the old path (every brick
told of every tick) for the comparison; the script runs both when --compare is given.
Run:  python benchmarks/sumo_bricks.py [--seconds 20] [--repeat 2] [--compare]
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[1]
SUMO = ROOT / "examples" / "sumo.py"
MOVES = """
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from time import sleep
tank = MoveTank(OUTPUT_B, OUTPUT_C)
while True:
    tank.on_for_seconds(30, 30, 0.8)
    tank.on_for_degrees(30, -30, 180)
    sleep(0.3)
    tank.on_for_seconds(-30, -30, 0.8)
"""


def world_alone(world, robots: int, seconds: float) -> float:
    sim = Simulation(world, [(f"robot{i + 1}", world.robot, world.starts[i]) for i in range(robots)])
    for robot in sim.robots:
        for motor, speed in ((robot.left, "200"), (robot.right, "-200")):  # turning on the spot
            motor.write("speed_sp", speed)
            motor.write("command", "run-forever")
    sensors = [s for robot in sim.robots for s in robot.sensors.values()]
    ticks = int(round(seconds * 1e6 / sim.tick_us))
    start = time.perf_counter()
    now = 0
    for _ in range(ticks):
        now += sim.tick_us
        sim.tick(now)
        for sensor in sensors:
            sensor.values()
    return seconds / (time.perf_counter() - start)


def with_bricks(world, program: Path, robots: int, seconds: float) -> float:
    result = run_programs([program] * robots, world, time_limit_s=seconds)
    assert result.status == "time_limit", result.reason
    return result.sim_time_s / result.wall_time_s


def table(world, seconds: float, repeat: int, moves: Path) -> list[tuple]:
    rows = []
    for robots in (1, 2, 4):
        alone = max(world_alone(world, robots, seconds) for _ in range(repeat))
        sumo = max(with_bricks(world, SUMO, robots, seconds) for _ in range(repeat))
        waits = max(with_bricks(world, moves, robots, seconds) for _ in range(repeat))
        rows.append((robots, alone, sumo, waits))
    return rows


def show(title: str, rows: list[tuple]) -> None:
    print(title)
    print("robots  world alone   sumo bricks (ratio)   moves bricks (ratio)")
    for robots, alone, sumo, waits in rows:
        print(
            f"{robots:6}  {alone:10.0f}x  {sumo:10.0f}x ({sumo / alone:4.2f})  {waits:10.0f}x ({waits / alone:4.2f})"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated seconds per measurement")
    parser.add_argument("--repeat", type=int, default=2, help="measurements of each; the best is reported")
    parser.add_argument("--compare", action="store_true", help="also with EV3SIM2D_EVERY_TICK=1 (old path)")
    args = parser.parse_args()
    world = load_maze(find_maze("sumo-4"))
    with tempfile.TemporaryDirectory() as folder:
        moves = Path(folder) / "moves.py"
        moves.write_text(MOVES)
        if args.compare:
            os.environ["EV3SIM2D_EVERY_TICK"] = "1"
            show(
                "every brick told of every tick (EV3SIM2D_EVERY_TICK=1):",
                table(world, args.seconds, args.repeat, moves),
            )
            del os.environ["EV3SIM2D_EVERY_TICK"]
        show("as configured:", table(world, args.seconds, args.repeat, moves))
    print(f"cores: {os.cpu_count()}; load average {os.getloadavg()[0]:.2f} (the figures move with it)")


if __name__ == "__main__":
    main()
