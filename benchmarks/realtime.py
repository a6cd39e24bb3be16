#!/usr/bin/env python3
"""How much faster than real time ev3sim2d runs, measured in one run on this machine.

(a) the world alone: one robot driving an arc in mazes/line.yaml, its four
    sensors read every tick (no program, no brick);
(b) a busy-loop proportional line follower written against the ev3dev2 shim
    (examples/line_follower.py) in mazes/line.yaml, in its sandboxed brick process:
    program, brick, protocol, simulator and world;
(c) the same program in the brick process without the sandbox (what the sandbox costs);
(d) the same program run the way ev3sim2d ran it before bricks existed, in the simulator's own
    process (the code of commit old_code.IN_PROCESS_COMMIT, taken from git), for the ratio (b)/(d);
(e) the same program in its sandboxed brick on the portable path (EV3SIM2D_PORTABLE=1: the brick
    connects over loopback TCP, as on Windows, with no shared memory), for the ratio (e)/(b);
(f) the same line follower written against the Pybricks shim as LEGO's EV3 MicroPython example is
    (examples/pybricks/line_follower.py: a ColorSensor's reflection(), a DriveBase's drive() and
    wait(10) each time round), in its sandboxed brick, for the ratio (f)/(b) (target: within 20 %).
    (Without the wait it goes round six times as often per simulated second as (b), as on a brick,
    where Pybricks' calls cost less than python-ev3dev2's: it then costs more per simulated second.)

Target: (b) at least 300x real time.  Each figure is the best of --repeat runs; the machine is
shared, so the figures move with its load: compare the ratios of one run.
Run:  python benchmarks/realtime.py [--seconds 60] [--repeat 3]
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from old_code import old_code

from ev3sim2d.simulator.bricks import PORTABLE
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[1]
FOLLOWER = ROOT / "examples" / "line_follower.py"
PYBRICKS_FOLLOWER = ROOT / "examples" / "pybricks" / "line_follower.py"

IN_PROCESS_RUN = """
import sys
# an editable install's finder would bring today's ev3sim2d: take the old one from PYTHONPATH
sys.meta_path = [f for f in sys.meta_path if not type(f).__module__.startswith("__editable__")]
import ev3sim2d
assert ev3sim2d.__file__.startswith({folder!r}), ev3sim2d.__file__
from ev3sim2d.run import run_programs
from ev3sim2d.world.maze_file import find_maze, load_maze
world = load_maze(find_maze("line"))
best = 0.0
for _ in range({repeat}):
    result = run_programs([{program!r}], world, time_limit_s={seconds})
    assert result.status == "time_limit", result.reason
    best = max(best, result.sim_time_s / result.wall_time_s)
print(best)
"""


def world_alone(world, seconds: float, clock=time.perf_counter) -> float:
    """Real-time factor of the world stepping one robot and reading its four sensors every tick (by `clock`:
    the wall clock, or this process's CPU time)."""
    sim = Simulation(world, [("robot", world.robot, world.start)])
    robot = sim.robots[0]
    for motor, speed in ((robot.left, "240"), (robot.right, "300")):  # a left arc that stays clear of walls
        motor.write("speed_sp", speed)
        motor.write("command", "run-forever")
    sensors = list(robot.sensors.values())
    ticks = int(round(seconds * 1e6 / sim.tick_us))
    start = clock()
    now = 0
    for _ in range(ticks):
        now += sim.tick_us
        sim.tick(now)
        for sensor in sensors:
            sensor.values()
    return seconds / (clock() - start)


def line_follower(
    world, seconds: float, sandbox: bool = True, portable: bool = False, program: Path = FOLLOWER
) -> float:
    """Real-time factor of a shim's line follower in its brick (simulation wall time, not start-up)."""
    previous = os.environ.get(PORTABLE)
    os.environ[PORTABLE] = "1" if portable else "0"
    try:
        result = run_programs([program], world, time_limit_s=seconds, sandbox=sandbox)
    finally:
        if previous is None:
            del os.environ[PORTABLE]
        else:
            os.environ[PORTABLE] = previous
    assert result.status == "time_limit", result.reason
    return result.sim_time_s / result.wall_time_s


def in_process(seconds: float, repeat: int) -> float | None:
    """The line follower as ev3sim2d ran it before bricks (from git); None without the history."""
    with tempfile.TemporaryDirectory(prefix="ev3sim2d-in-process-") as scratch:
        tree = old_code(Path(scratch))
        if tree is None:
            return None
        code = IN_PROCESS_RUN.format(repeat=repeat, program=str(FOLLOWER), seconds=seconds, folder=str(tree))
        env = {**os.environ, "PYTHONPATH": str(tree), "PYTHONHASHSEED": "0"}
        ran = subprocess.run(
            [sys.executable, "-c", code], cwd=tree, env=env, capture_output=True, text=True, timeout=900
        )
        if ran.returncode != 0:
            print(f"(d) failed: {ran.stderr.strip()[-500:]}")
            return None
        return float(ran.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated seconds per measurement")
    parser.add_argument("--repeat", type=int, default=3, help="measurements of each; the best is reported")
    args = parser.parse_args()
    world = load_maze(find_maze("line"))
    a = max(world_alone(world, args.seconds) for _ in range(args.repeat))
    b = max(line_follower(world, args.seconds) for _ in range(args.repeat))
    c = max(line_follower(world, args.seconds, sandbox=False) for _ in range(args.repeat))
    d = in_process(args.seconds, args.repeat)
    e = max(line_follower(world, args.seconds, portable=True) for _ in range(args.repeat))
    f = max(line_follower(world, args.seconds, program=PYBRICKS_FOLLOWER) for _ in range(args.repeat))
    print(f"(a) world alone, 4 sensors read every tick:          {a:7.0f}x real time")
    print(f"(b) line follower in its sandboxed brick process:     {b:7.0f}x real time")
    print(f"(c) line follower in its brick, no sandbox:            {c:7.0f}x real time")
    if d is not None:
        print(f"(d) line follower in the simulator's process (old):    {d:7.0f}x real time")
    print(f"(e) line follower, portable path (loopback TCP):       {e:7.0f}x real time")
    print(f"(f) Pybricks line follower in its sandboxed brick:    {f:7.0f}x real time")
    old = f"(b)/(d) = {b / d:.2f}   " if d is not None else ""
    print(f"{old}(b)/(a) = {b / a:.2f}   (e)/(b) = {e / b:.2f}   (f)/(b) = {f / b:.2f}")
    print("targets: (b) >= 300x; (f)/(b) >= 0.8")
    print(f"cores: {os.cpu_count()}; load average {os.getloadavg()[0]:.2f} (the figures move with it)")


if __name__ == "__main__":
    main()
