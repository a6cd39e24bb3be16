"""Which cores a run's processes use: with several bricks, a core of its own for the simulator.

The simulator and its bricks hand the turn to each other every tick, through
shared memory, and each spins while it waits.  A hand-over costs 3.6 us between
two cores that spin, 6 us on one core where the waiting side spins and yields
it, 13 to 34 us where the waiting side sleeps and is woken by a system call
(benchmarks/hand_over.py, 2 cores).  With more processes than cores, spinning
only pays if no brick shares the simulator's core: the simulator spins on the
bricks' markers and steps the world, and a brick there would wait for it.  So
with two bricks or more, on a machine nobody else keeps busy, the simulator
keeps the first core it may use and the bricks take the others in turn (on two
cores: all on the second, where they spin and yield it to each other).  A brick
is a tree of processes (the one started, and the sandboxed one it forks to run
the program): each is placed as it starts, so that what it forks inherits its
core, and the whole tree again as the run begins, whatever forked when.
Measured on 2 cores (benchmarks/robots.py): two line followers on line-shared
went from 65-95x real time to 175-210x, four sumo robots from 15-29x to 55-63x.
One brick needs none of this (the scheduler puts the two processes on two cores
by itself).

Only where the system lets a process choose its cores (os.sched_setaffinity:
Linux); elsewhere, more spinning processes than cores do not spin at all
(protocol/stream.cores_idle).  Nothing of this changes what a run does, only how
fast: the world and the bricks meet in virtual time whatever runs where.
"""

from __future__ import annotations

import os

from ..protocol.stream import machine_busy, spinning_processes


class RunCores:
    """The cores of one run: decided before its bricks start, each brick placed as it starts (brick_started),
    the simulator placed for the run itself (start), and everything put back at its end (end: a video is
    encoded afterwards, on every core)."""

    def __init__(self, bricks: int, spin: bool, place: bool = True) -> None:
        """bricks: how many the run starts; spin: whether it may spin at all (not when other runs share its
        cores); place: whether it may choose cores (only a run that has the machine to itself: not one of a
        class graded in parallel, whose grader shares the cores out, grading/grader.py)."""
        self._choose = getattr(os, "sched_setaffinity", None)
        self._allowed = sorted(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else []
        ours = self._ours = 1 + bricks
        self.shared = bool(
            spin
            and place
            and self._choose is not None
            and bricks >= 2
            and len(self._allowed) >= 2
            and not machine_busy()  # (a look before our bricks start: others' processes only)
        )
        spinning_processes(ours if spin else 2, self.shared)
        self._bricks: list[tuple[int, int]] = []  # (index, pid) of each brick started

    def brick_started(self, index: int, pid: int) -> None:
        """Brick `index` (the process started: pid) runs on a core of the bricks' from now on."""
        if self.shared:
            self._bricks.append((index, pid))
            self._place(index, [pid])

    def start(self) -> None:
        """The run begins: the simulator (this thread) on the core of its own, and every process of each
        brick on its core (one forked before its parent was placed would run anywhere)."""
        if not self.shared:
            return
        for index, pid in self._bricks:
            self._place(index, _tree(pid))
        if self.shared:
            try:
                self._choose(0, {self._allowed[0]})
            except OSError:
                self._give_up()

    def _place(self, index: int, pids: list[int]) -> None:
        core = {self._allowed[1:][index % (len(self._allowed) - 1)]}
        try:
            for pid in pids:
                for thread in _threads(pid):
                    self._choose(thread, core)
        except OSError:  # (gone already, or refused: the scheduler's choice, and no spinning on so many)
            self._give_up()

    def end(self) -> None:
        if self.shared:
            self._choose(0, set(self._allowed))
        spinning_processes(2, False)

    def _give_up(self) -> None:
        self.shared = False
        spinning_processes(self._ours, False)


def _tree(pid: int) -> list[int]:
    """A process and its descendants, as /proc lists each thread's children (none found: the process)."""
    found, stack = [], [pid]
    while stack:
        parent = stack.pop()
        found.append(parent)
        for thread in _threads(parent):
            try:
                with open(f"/proc/{parent}/task/{thread}/children") as f:
                    stack += [int(child) for child in f.read().split()]
            except (OSError, ValueError):
                pass
    return found


def _threads(pid: int) -> list[int]:
    """The threads of a process (a core is chosen thread by thread; those it starts later inherit it)."""
    try:
        return [int(name) for name in os.listdir(f"/proc/{pid}/task")]
    except (OSError, ValueError):
        return [pid]
