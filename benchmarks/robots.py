#!/usr/bin/env python3
"""How the cost of a run grows with its robots (issue 28), measured in one run on this machine.

For 1, 2 and 4 robots in mazes/sumo-4.yaml:
- the world alone: the robots' motors driven as examples/sumo.py drives them (turn on the spot, charge
  at what the ultrasonic sensor sees within 70 cm, back off and turn away from the black line), every
  sensor of every robot read every tick, in this process (no program, no brick);
- with their bricks: N copies of examples/sumo.py, each in its sandboxed brick (run_programs): busy
  bricks, reading two sensors and writing their motors each time round;
- waiting bricks: N copies of a program of blocking moves (on_for_seconds, on_for_degrees, sleep), which
  waits for its motors most of the time: what a brick's "nothing from me before t" saves (docs/protocol.md,
  Quiet waits);
- the world alone with the robots apart: each turning on the spot where it starts, every sensor read every
  tick, so that they never touch: the cost of more robots without the cost of their meeting;
each as a multiple of real time (simulated seconds per wall second, the best of --repeat), and per row
the cost of N robots relative to one (world alone: the one-robot figure / the N-robot one) and what is
left of the world's speed with the bricks (with bricks / world alone).

Targets (issue 28): four robots' world at most 3.5x the cost of one; four bricks at least 0.6 of the
world alone's speed; four sumo bricks at least 100x real time, two line followers at least 250x.  The machine may be shared: compare the ratios of one run.
Run:  python benchmarks/robots.py [--seconds 30] [--world-seconds 120] [--repeat 2] [--robots 1 2 4]
      [--world-only] [--cpu] [--compare] [--unplaced]
(--cpu: the world alone timed by the process's CPU time, on a loaded machine; --compare: the bricks also
told of every tick, the old path, EV3SIM2D_EVERY_TICK=1, in the same run; --unplaced: also with the
processes where the scheduler puts them, the old path: run_programs(place=False))
Also: examples/line_follower.py alone on mazes/line.yaml and two of them on line-shared.yaml.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from ev3sim2d.simulator.run import new_simulation, run_programs
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[1]
SUMO = ROOT / "examples" / "sumo.py"
FOLLOWER = ROOT / "examples" / "line_follower.py"
WORLD = "sumo-4"
BORDER = 30  # as examples/sumo.py: reflected light below this is the ring's black line
SEES_MM = 700  # ... and something nearer than 70 cm ahead is another robot (US-DIST-CM reads mm)
# Issue 28's targets were set in times real time on a quiet 2-core machine where one robot's world alone
# (this script's first row) ran at 626x and the single line follower with its brick at about 600x.
ISSUE_REFERENCE = {"world alone, one robot": 626, "one line follower": 600}
ISSUE_TARGETS = {"four sumo bricks": 100, "two line followers": 250}
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


class SumoDriver:
    """examples/sumo.py's loop, written against one robot's devices: it reads every sensor each tick and
    writes its motors only when what it does changes (as the shim sends only what changed)."""

    def __init__(self, robot) -> None:
        self.left, self.right = robot.left, robot.right
        self.sensors = list(robot.sensors.values())
        self.floor = next(s for s in self.sensors if s.spec.kind == "color")
        self.eyes = next(s for s in self.sensors if s.spec.kind == "ultrasonic")
        self.doing = ""

    def _run(
        self, doing: str, command: str, left: int, right: int, setting: str = "", value: int = 0
    ) -> None:
        """Both wheels at left and right % of max_speed (a setting, such as time_sp, for each)."""
        if doing == self.doing:
            return
        self.doing = doing
        for motor, speed in ((self.left, left), (self.right, right)):
            motor.write("speed_sp", str(speed * motor.max_speed // 100))
            if setting:
                motor.write(setting, str(value if speed >= 0 or setting == "time_sp" else -value))
            motor.write("command", command)

    def _moving(self) -> bool:
        return "running" in self.left.read("state") or "running" in self.right.read("state")

    def tick(self) -> None:
        for sensor in self.sensors:
            sensor.values()
        if self.doing in ("back", "turn") and self._moving():
            return  # a blocking move of the program: on_for_seconds, on_for_degrees
        if self.doing == "back":
            self._run("turn", "run-to-rel-pos", 50, -50, "position_sp", 200)  # on_for_degrees(50, -50, 200)
        elif self.floor.values()[0] < BORDER:
            self._run("back", "run-timed", -50, -50, "time_sp", 600)
        elif self.eyes.values()[0] < SEES_MM:
            self._run("charge", "run-forever", 100, 100)
        else:
            self._run("look", "run-forever", 25, -25)


class Turner(SumoDriver):
    """Every sensor read each tick, the robot turning on the spot where it started: robots that never touch
    (they start 60 cm apart), though their sensors still see each other."""

    def tick(self) -> None:
        for sensor in self.sensors:
            sensor.values()
        self._run("look", "run-forever", 25, -25)


def world_alone(world, robots: int, seconds: float, clock=time.perf_counter, driver=SumoDriver) -> float:
    """Real-time factor of the world stepping `robots` sumo robots, all their sensors read every tick
    (by `clock`: the wall clock, or this process's CPU time, steadier on a loaded machine); driver: how
    they drive (SumoDriver: as examples/sumo.py, pushing each other; Turner: on the spot, apart)."""
    sim, _ = new_simulation(world, robots, None, 0, None)
    drivers = [driver(robot) for robot in sim.robots]
    ticks = int(round(seconds * 1e6 / sim.tick_us))
    start = clock()
    now = 0
    for _ in range(ticks):
        now += sim.tick_us
        sim.tick(now)
        for driver in drivers:
            driver.tick()
    return seconds / (clock() - start)


def with_bricks(world, robots: int, seconds: float, program: Path = SUMO, place: bool = True) -> float:
    """Real-time factor of `robots` copies of a program in their sandboxed bricks (run time only); place:
    False leaves the processes where the scheduler puts them (simulator/cores.py)."""
    result = run_programs([program] * robots, world, time_limit_s=seconds, place=place)
    assert result.status == "time_limit", result.reason
    return result.sim_time_s / result.wall_time_s


def table(world, args, clock, moves: Path, place: bool = True) -> list[tuple]:
    """(robots, world alone, busy bricks, waiting bricks, world alone with the robots apart) per row; None
    where not measured."""
    rows = []
    for n in args.robots:
        alone = max(world_alone(world, n, args.world_seconds, clock) for _ in range(args.repeat))
        apart = max(world_alone(world, n, args.world_seconds, clock, Turner) for _ in range(args.repeat))
        busy = waiting = None
        if not args.world_only:
            busy = max(with_bricks(world, n, args.seconds, place=place) for _ in range(args.repeat))
            waiting = max(with_bricks(world, n, args.seconds, moves, place) for _ in range(args.repeat))
        rows.append((n, alone, busy, waiting, apart))
    return rows


def line_followers(args, place: bool = True) -> tuple[float, float]:
    """examples/line_follower.py: one on mazes/line.yaml, and two on line-shared.yaml (x real time)."""
    one = max(
        with_bricks(load_maze(find_maze("line")), 1, args.seconds, FOLLOWER) for _ in range(args.repeat)
    )
    shared = load_maze(find_maze("line-shared"))
    two = max(with_bricks(shared, 2, args.seconds, FOLLOWER, place) for _ in range(args.repeat))
    return one, two


def show(title: str, rows: list[tuple]) -> None:
    print(title)
    print(
        "| robots | world alone | cost vs one robot | sumo bricks | / world | waiting bricks | / world "
        "| world alone, robots apart | cost vs one robot |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    one, one_apart = (rows[0][1], rows[0][4]) if rows[0][0] == 1 else (None, None)
    for n, alone, busy, waiting, apart in rows:
        cost = f"{one / alone:.2f}x" if one else "-"
        cost_apart = f"{one_apart / apart:.2f}x" if one_apart else "-"
        cells = [f"{b:.0f}x | {b / alone:.2f}" if b is not None else "- | -" for b in (busy, waiting)]
        print(f"| {n} | {alone:.0f}x | {cost} | {cells[0]} | {cells[1]} | {apart:.0f}x | {cost_apart} |")


def scaled_targets(rows: list[tuple], one_follower: float, two_followers: float) -> None:
    """The two targets in times real time, as the ratios to a reference they were on the machine they were
    set on (ISSUE_REFERENCE), and this run's figures as the same ratios: on a machine slower or busier than
    that one, the ratio says whether a target is met where the real-time factor cannot."""
    by_robots = {n: (alone, busy) for n, alone, busy, _, _ in rows}
    if 1 in by_robots and 4 in by_robots and by_robots[4][1] is not None:
        reference, target = ISSUE_REFERENCE["world alone, one robot"], ISSUE_TARGETS["four sumo bricks"]
        ratio = by_robots[4][1] / by_robots[1][0]
        print(
            f"four sumo bricks / one robot's world alone: {ratio:.3f} (target {target}/{reference} = "
            f"{target / reference:.3f}, the same as {ratio * reference:.0f}x on that machine)"
        )
    reference, target = ISSUE_REFERENCE["one line follower"], ISSUE_TARGETS["two line followers"]
    ratio = two_followers / one_follower
    print(
        f"two line followers / one line follower: {ratio:.3f} (target {target}/{reference} = "
        f"{target / reference:.3f}, the same as {ratio * reference:.0f}x on that machine)"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated seconds of a run with bricks")
    parser.add_argument("--world-seconds", type=float, default=120.0, help="simulated seconds, world alone")
    parser.add_argument("--repeat", type=int, default=2, help="measurements of each; the best is reported")
    parser.add_argument("--robots", type=int, nargs="+", default=[1, 2, 4], help="rows: numbers of robots")
    parser.add_argument("--world-only", action="store_true", help="measure the world alone (no bricks)")
    parser.add_argument(
        "--cpu", action="store_true", help="the world alone by this process's CPU time, not the wall clock"
    )
    parser.add_argument("--compare", action="store_true", help="also with every brick told of every tick")
    parser.add_argument(
        "--unplaced", action="store_true", help="also with the processes where the scheduler puts them"
    )
    args = parser.parse_args()
    clock = time.process_time if args.cpu else time.perf_counter
    world = load_maze(find_maze(WORLD))
    clocked = "world alone by CPU time" if args.cpu else "wall clock"
    print(f"{WORLD}; best of {args.repeat}; x real time ({clocked})")
    with tempfile.TemporaryDirectory() as folder:
        moves = Path(folder) / "moves.py"
        moves.write_text(MOVES)
        if args.compare:
            os.environ["EV3SIM2D_EVERY_TICK"] = "1"
            try:
                show(
                    "every brick told of every tick (EV3SIM2D_EVERY_TICK=1):",
                    table(world, args, clock, moves),
                )
            finally:
                del os.environ["EV3SIM2D_EVERY_TICK"]
        if args.unplaced:
            show(
                "processes where the scheduler puts them (place=False):",
                table(world, args, clock, moves, False),
            )
        rows = table(world, args, clock, moves)
        show("as configured:", rows)
    if not args.world_only:
        if args.unplaced:
            one, two = line_followers(args, place=False)
            print(
                f"line followers, where the scheduler puts them: one on line {one:.0f}x, two on line-shared "
                f"{two:.0f}x ({two / one:.2f} of one)"
            )
        one, two = line_followers(args)
        print(
            f"line followers: one on line {one:.0f}x, two on line-shared {two:.0f}x ({two / one:.2f} of one)"
        )
    print("targets: four robots' world at most 3.5x one robot's cost; four bricks at least 0.6 of the world;")
    print("four sumo bricks at least 100x real time; two line followers on line-shared at least 250x")
    if not args.world_only:
        scaled_targets(rows, one, two)
    print(f"cores: {os.cpu_count()}; load average {os.getloadavg()[0]:.2f} (the figures move with it)")


if __name__ == "__main__":
    main()
