#!/usr/bin/env python3
"""What one hand-over between the simulator and a brick costs, by where the two processes run and how
they wait (the figures simulator/cores.py is designed from).

A hand-over is one message through the brick connection's shared memory (protocol/shared_memory.py) and
the answer back: the simulator sends a snapshot-sized message, the brick answers with a tick marker.
Measured as a round trip, halved, in four set-ups:
- two cores, both spin: each process on a core of its own, spinning while it waits;
- two cores, both sleep: as above, but each sleeps and is woken by a system call;
- one core, both spin: the two processes on the same core, spinning and yielding the core;
- one core, both sleep: the same core, each sleeping until woken (the core changes hands at each wake-up).
Plus, with several bricks on one core (the simulator alone on the other): a round of messages to each
brick and back, per brick, spinning, as a run of several bricks on two cores does each tick.

Linux only (os.fork, os.memfd_create, os.sched_setaffinity: the shared memory channel's and cores.py's
own conditions).  Run:  python benchmarks/hand_over.py [--rounds 20000]
"""

from __future__ import annotations

import argparse
import os
import socket
import sys
import time

from ev3sim2d.protocol import shared_memory, stream

SNAPSHOT = ["snap", 1_230_000, ["42", "running"]]
MARKER = ["ops", [["w", 3, "250"], ["t", 1_240_000]]]


def _pair(spin: bool) -> tuple[shared_memory.SharedChannel, socket.socket, int]:
    """The simulator's end, and what the brick's end is made of (its socket and memory fd)."""
    ours, theirs = socket.socketpair()
    memory = shared_memory.create_memory()
    brick_fd = os.dup(memory)
    channel = shared_memory.SharedChannel(ours, memory, simulator=True, spin_s=0.002 if spin else 0.0)
    return channel, theirs, brick_fd


def _brick(sock: socket.socket, memory_fd: int, core: int, rounds: int) -> None:
    """A forked brick: answer each snapshot with a marker, `rounds` times, on `core`."""
    os.sched_setaffinity(0, {core})
    channel = shared_memory.SharedChannel(sock, memory_fd, simulator=False)
    for _ in range(rounds):
        channel.receive()
        channel.send(MARKER)
    os._exit(0)


def round_trips(cores: tuple[int, int], spin: bool, rounds: int, bricks: int = 1) -> float:
    """Microseconds a hand-over costs: the simulator on cores[0], each brick on cores[1]; a round sends a
    snapshot to each brick, then takes each one's marker."""
    stream.spinning_processes(1 + bricks, own_cores=spin)
    channels, children = [], []
    for _ in range(bricks):
        channel, theirs, brick_fd = _pair(spin)
        pid = os.fork()
        if pid == 0:
            _brick(theirs, brick_fd, cores[1], rounds)
        theirs.close()
        os.close(brick_fd)
        channels.append(channel)
        children.append(pid)
    os.sched_setaffinity(0, {cores[0]})
    try:
        for channel in channels:  # (a first round: every brick up)
            channel.send(SNAPSHOT)
        for channel in channels:
            channel.receive()
        start = time.perf_counter()
        for _ in range(rounds - 1):
            for channel in channels:
                channel.send(SNAPSHOT)
            for channel in channels:
                channel.receive()
        spent = time.perf_counter() - start
    finally:
        for pid in children:
            os.waitpid(pid, 0)
        os.sched_setaffinity(0, set(range(os.cpu_count() or 1)))
        stream.spinning_processes(2, False)
    return spent / (rounds - 1) / bricks / 2 * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=20_000, help="round trips in each measurement")
    args = parser.parse_args()
    if not (hasattr(os, "fork") and shared_memory.available() and hasattr(os, "sched_setaffinity")):
        sys.exit("needs os.fork, the shared memory channel and os.sched_setaffinity (Linux on x86-64)")
    if len(os.sched_getaffinity(0)) < 2:
        sys.exit("needs two cores")
    first, second = sorted(os.sched_getaffinity(0))[:2]
    rows = [
        ("two cores, both spin", (first, second), True, 1),
        ("two cores, both sleep", (first, second), False, 1),
        ("one core, both spin", (first, first), True, 1),
        ("one core, both sleep", (first, first), False, 1),
        ("4 bricks on one core, simulator on the other, all spin", (first, second), True, 4),
        ("4 bricks on one core, simulator on the other, all sleep", (first, second), False, 4),
    ]
    print(f"one hand-over (half a round trip), microseconds; {args.rounds} round trips each")
    for name, cores, spin, bricks in rows:
        rounds = args.rounds if spin else args.rounds // 10
        print(f"{name:58s} {round_trips(cores, spin, rounds, bricks):8.1f} us")
    print(f"cores: {os.cpu_count()}; load average {os.getloadavg()[0]:.2f} (the figures move with it)")


if __name__ == "__main__":
    main()
