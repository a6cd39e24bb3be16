#!/usr/bin/env python3
"""The simulator's own work per tick in a run of several bricks, without the bricks: what caps such a run.

A run of bricks goes as fast as the slower of two things allows: the simulator (the world's tick, the
snapshots' sensor readings, taking in and applying the bricks' messages) and the bricks themselves.  On a
shared machine a run's real-time factor moves with the machine's load by half or more between two runs
(the world alone varies so too), which hides what a change to the simulator does.  So this measures the
simulator's part alone, by CPU time:

1. record: run the programs in their sandboxed bricks (run_programs) and keep every message each brick
   sent, as it came;
2. replay: run a new session of the same world, whose bricks are those recordings (each message decoded
   when the session takes it, each message to a brick encoded and dropped), and time it by this process's
   CPU time.  The replay must move the robots exactly as the recorded run did (checked: the trace's
   motion), or it measured something else;
3. reference, in the same run: the world stepping alone with one robot, its sensors read every tick
   (benchmarks/realtime.py's (a), timed by CPU time).

Printed per scenario: the replay's microseconds a tick (best of --repeat), that as a multiple of the
reference's, and the real-time factor it allows at most (a tick of 10 ms in that many microseconds).
Scenarios: four copies of examples/sumo.py on mazes/sumo-4.yaml, and two of examples/line_follower.py on
mazes/line-shared.yaml (issue 28's targets: 100x and 250x real time with their bricks).
Run:  python benchmarks/simulator_work.py [--seconds 20] [--repeat 5]
"""

from __future__ import annotations

import argparse
import hashlib
import time
from pathlib import Path

from realtime import world_alone

from ev3sim2d.protocol import ProtocolError
from ev3sim2d.protocol.messages import decode, encode
from ev3sim2d.simulator.brick_port import BrickPort
from ev3sim2d.simulator.run import new_simulation, run_programs
from ev3sim2d.simulator.session import Session
from ev3sim2d.simulator.simulation import TICK_US
from ev3sim2d.world.maze_file import find_maze, load_maze

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = {
    "four sumo robots": ("sumo-4", ROOT / "examples" / "sumo.py", 4),
    "two line followers": ("line-shared", ROOT / "examples" / "line_follower.py", 2),
}
HANG_AFTER_S = 5.0  # (run_programs' default)


class RecordedBrick:
    """A brick's connection that says again what a recorded brick said, message by message."""

    peer_may_defer = False
    closed = False

    def __init__(self, lines: list[bytes]) -> None:
        self.lines = lines
        self.next = 0

    def pending(self) -> list | None:
        if self.next == len(self.lines):
            return None
        self.next += 1
        return decode(self.lines[self.next - 1])

    def receive(self, timeout_s: float | None = None) -> list:
        message = self.pending()
        if message is None:
            raise ProtocolError("the recording ends here")
        return message

    def send(self, message: list) -> None:
        encode(message)  # the simulator's work of sending; nobody reads it

    def data_waiting(self) -> bool:
        return self.next < len(self.lines)

    def fileno(self) -> int:
        return -1

    def asleep(self, flag: bool) -> None:
        pass


def _motion(trace) -> str:
    return hashlib.sha256(trace.motion().tobytes()).hexdigest()[:16]


def record(maze: str, program: Path, robots: int, seconds: float) -> tuple[list[list[bytes]], str, float]:
    """Each brick's messages (encoded, as they came), the run's motion digest and its real-time factor."""
    lines: list[list[bytes]] = [[] for _ in range(robots)]
    accept = BrickPort.accept

    def kept(port: BrickPort, message: list) -> None:
        lines[port.index].append(encode(message)[:-1])
        accept(port, message)

    BrickPort.accept = kept
    try:
        result = run_programs([program] * robots, load_maze(find_maze(maze)), time_limit_s=seconds)
    finally:
        BrickPort.accept = accept
    assert result.status == "time_limit", result.reason
    return lines, _motion(result.trace), result.sim_time_s / result.wall_time_s


def replay(maze: str, lines: list[list[bytes]], seconds: float) -> tuple[float, str]:
    """CPU microseconds a tick of the session that replays these bricks, and its motion digest."""
    sim, presses = new_simulation(load_maze(find_maze(maze)), len(lines), None, 0, None)
    ports = [
        BrickPort(i, sim.robots[i], RecordedBrick(said), sim.trace, presses, [])
        for i, said in enumerate(lines)
    ]
    session = Session(sim, ports, int(round(seconds * 1e6)), HANG_AFTER_S, [], None, spin=False)
    start = time.process_time()
    session.run()
    spent = time.process_time() - start
    return spent / sim.ticks * 1e6, _motion(sim.trace)


def reference(seconds: float) -> float:
    """CPU microseconds a tick of the world alone, as benchmarks/realtime.py's (a) measures it: one robot
    on mazes/line.yaml, driving an arc with its four sensors read every tick."""
    return TICK_US / world_alone(load_maze(find_maze("line")), seconds, time.process_time)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated seconds of each run")
    parser.add_argument("--repeat", type=int, default=5, help="replays (and references); the best is kept")
    args = parser.parse_args()
    print(
        f"best of {args.repeat}, by CPU time; reference: the world alone, one robot on line (see the docstring)"
    )
    print("| scenario | recorded run | simulator's own work | / reference | allows at most |")
    print("|---|---|---|---|---|")
    for name, (maze, program, robots) in SCENARIOS.items():
        lines, motion, recorded = record(maze, program, robots, args.seconds)
        best = ref = float("inf")
        for _ in range(args.repeat):
            work, replayed = replay(maze, lines, args.seconds)
            if replayed != motion:
                raise SystemExit(f"{name}: the replay moved the robots otherwise than the run: not measured")
            best = min(best, work)
            ref = min(ref, reference(args.seconds / 2))
        print(
            f"| {name} ({robots} bricks, {maze}) | {recorded:.0f}x | {best:.1f} us/tick | {best / ref:.2f} | "
            f"{TICK_US / best:.0f}x |"
        )


if __name__ == "__main__":
    main()
