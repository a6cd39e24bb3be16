"""Bricks and the world in lockstep over virtual time: the simulator's turn-taking.

Each brick runs ahead on its own clock and says when it passes a tick (a tick
marker).  The world steps to a tick only once every brick still running has
passed it (conservative lockstep, as in parallel discrete-event simulation),
and the bricks waiting there get their snapshot.  Between ticks a brick's ops
touch only its own robot's devices, so the bricks' ops between two ticks can
be applied brick by brick: the run depends only on what the programs do, never
on which process was faster.  The simulator never waits for a brick that is
ahead; a brick that is behind and silent for `hang_after_s` of real time (a
program spinning without using the robot or the clock) is stopped.  A robot whose
program ended (or whose brick was dropped) while others run on is let go, as an
EV3's brickman does when a program ends: its motors are reset (Simulation.let_go).
"""

from __future__ import annotations

import gc
import time

from ..protocol import ConnectionGone, ProtocolError, wait_for_any
from ..protocol.stream import cores_idle
from .brick_port import BrickPort
from .simulation import Simulation

_monotonic = time.monotonic
_perf_counter = time.perf_counter
SPIN_S = 0.002
BAD_MESSAGE = (ProtocolError, TypeError, ValueError, IndexError, KeyError, AttributeError, OverflowError)


def _why(err: Exception) -> str:
    return f"gone: {err}" if isinstance(err, ConnectionGone) else f"protocol: {err}"


class Session:
    """Runs the world with its bricks until every brick has ended or the time limit."""

    def __init__(
        self,
        sim: Simulation,
        ports: list[BrickPort],
        limit_us: int | None,
        hang_after_s: float,
        printed: list | None = None,
        echo=None,
        spin: bool = True,
    ) -> None:
        """printed: the list the ports add printed lines to; echo(line) shows them, in time order."""
        self.spin_s = SPIN_S if spin else 0.0
        self.printed = printed if printed is not None else []
        self.echo = echo
        self.sim = sim
        self.ports = ports
        self.limit_us = limit_us
        self.hang_after_s = hang_after_s
        self.world_us = 0
        self.next_tick_us = sim.tick_us
        self.interrupted = False
        self.stop_us: int | None = None  # a stepped run's stop (advance): the world goes no further
        self.started = False
        self._let_go: set[int] = set()  # robots let go when their programs ended (Simulation.let_go)

    def _step_to(self, target_us: int) -> None:
        """Run the world's ticks up to target_us; after each, the snapshots bricks will need."""
        tick = self.sim.tick
        step = self.sim.tick_us
        while self.next_tick_us <= target_us:
            now = self.next_tick_us
            tick(now)
            self.next_tick_us += step
            self.world_us = now
            self._snapshots(now)
        self.world_us = target_us
        if self.printed:
            self._echo(target_us)

    def _echo(self, until_us: int | None) -> None:
        """Show the printed lines up to until_us (all: None) in time order, robot by robot."""
        lines = self.printed
        limit = None if until_us is None else until_us / 1e6
        lines.sort(key=lambda line: (line.t_s, line.robot))
        cut = (
            len(lines)
            if limit is None
            else next((i for i, x in enumerate(lines) if x.t_s > limit), len(lines))
        )
        shown, self.printed[:] = lines[:cut], lines[cut:]
        if self.echo is not None:
            for line in shown:
                self.echo(line)

    def _snapshots(self, tick_us: int) -> None:
        """After the tick at tick_us: a brick in [tick_us, +tick) will read from this snapshot next tick;
        one that jumped to tick_us + tick (a sleep) needs it at once.  Always taken, sent or not, so that
        the record never depends on which process was faster."""
        label = tick_us + self.sim.tick_us
        for port in self.ports:
            if not port.finished and port.declared in (tick_us, label):
                port.snapshot(label)

    def drop(self, port: BrickPort, why: str) -> None:
        """End a brick's part in the run (it broke the protocol, went away, or hung)."""
        if not port.finished:
            port.gone = why
        port.send(["stop", why])

    def _drain(self, port: BrickPort) -> None:
        """Apply whatever the brick has sent, as far as the world's time allows."""
        while True:
            try:
                port.run_ops(self.world_us)
                if port.finished or port.marker is not None:
                    return
                message = port.channel.pending()
                if message is None:
                    if port.broken:
                        self.drop(port, "gone: the brick closed the connection")
                    return
                port.accept(message)
                port.last_heard = _monotonic()
            except BAD_MESSAGE as err:
                self.drop(port, _why(err))
                return

    def run(self) -> None:
        self._heard_now()
        frozen_before = gc.get_freeze_count()  # a grading worker: what its grader froze before the fork
        gc.freeze()  # the world, the devices, the modules: a collection during the run skips them
        try:
            self._snapshots(0)
            self._run()
        except KeyboardInterrupt:
            self.interrupted = True
            for port in self.ports:
                self.drop(port, "interrupted")
        finally:
            if not frozen_before:  # (a worker ends soon: unfreezing would make it copy the grader's pages)
                gc.unfreeze()
        self.finish()

    def _heard_now(self) -> None:
        now = _monotonic()
        for port in self.ports:
            port.last_heard = now

    def finish(self) -> None:
        """The world to the moment the last brick ended (or the time limit), and every printed line shown."""
        end_us = max((p.time_us for p in self.ports), default=0)
        if self.limit_us is not None:
            end_us = min(end_us, self.limit_us)
        if not self.interrupted:
            self._step_to(max(end_us, self.world_us))
        self._echo(None)

    # ------------------------------------------------------------ a run in steps
    def advance(self, until_us: int) -> bool:
        """Run until the world reaches until_us (a live run's pace, a pause, a step), every brick has
        ended, or the time limit; True when the run is over (then finish() ends it).  A brick is judged
        hung only by the silence within one call: a pause between calls is no one's fault."""
        if not self.started:
            self.started = True
            self._snapshots(0)
        self._heard_now()
        self.stop_us = until_us
        try:
            self._run()
        finally:
            self.stop_us = None
        return all(p.finished for p in self.ports) or (
            self.limit_us is not None and self.world_us >= self.limit_us
        )

    def _paused_before(self, target_us: int) -> bool:
        """A stepped run (advance) stops where it was asked to: the world to that moment, not past it."""
        if self.stop_us is None or target_us <= self.stop_us:
            return False
        if self.stop_us > self.world_us:
            self._step_to(self.stop_us)
        return True

    def _run_one(self, port: BrickPort) -> None:
        """_run for one brick (the common case), without the bookkeeping of several."""
        port.channel.peer_may_defer = True  # nobody else waits for the world while this brick computes
        limit = self.limit_us
        while port.end is None and port.gone is None:
            self._drain(port)
            if port.end is not None or port.gone is not None:
                return
            target = port.marker
            if target is None:
                self._wait([port])
                continue
            if limit is not None and target >= limit:
                return self._stop_at_limit([port])
            if self._paused_before(target):
                return
            self._step_to(target)
            port.marker = None

    def _stop_at_limit(self, live: list[BrickPort]) -> None:
        """Every brick still running has passed the time limit: the world runs to it, and the run ends."""
        self._step_to(self.limit_us)
        for port in live:
            port.time_us = self.limit_us
            port.end = {"t_us": self.limit_us, "status": "time_limit", "error": None}
            self.drop(port, "time limit")

    def _run(self) -> None:
        ports = self.ports
        if len(ports) == 1:
            return self._run_one(ports[0])
        limit = self.limit_us
        let_go = self._let_go
        while True:
            live = [p for p in ports if not p.finished]
            for port in live:
                self._drain(port)
            live = [p for p in live if not p.finished]
            if not live:
                return
            for port in ports:  # (ended here, or dropped while waiting)
                if port.finished and port.index not in let_go:
                    let_go.add(port.index)
                    self.sim.let_go(port.index)
            behind = [p for p in live if p.marker is None]
            if not behind:
                target = min(p.marker for p in live)
                if limit is not None and target >= limit:
                    return self._stop_at_limit(live)
                if self._paused_before(target):
                    return
                self._step_to(target)
                for port in live:
                    if port.marker == target:
                        port.marker = None
                continue
            self._wait(behind)

    def _wait(self, ports: list[BrickPort]) -> None:
        """Wait until one of these bricks (all behind the world) says something, or stop a silent one."""
        deadline = min(p.last_heard for p in ports) + self.hang_after_s
        if len(ports) == 1:
            port = ports[0]
            try:
                message = port.channel.receive(timeout_s=max(0.0, deadline - _monotonic()))
                if message is not None:
                    port.accept(message)
                    port.last_heard = _monotonic()
            except BAD_MESSAGE as err:
                self.drop(port, _why(err))
                return
        else:
            spin_end = _perf_counter() + (self.spin_s if cores_idle() else 0.0)
            heard = False
            while not heard:
                for port in ports:
                    if self._take(port):
                        heard = True
                if heard or _perf_counter() > spin_end:
                    break
            if not heard:
                channels = [p.channel for p in ports]
                try:
                    ready = wait_for_any(channels, max(0.0, min(0.05, deadline - _monotonic())))
                except ProtocolError:
                    ready = [c for c in channels if c.closed]
                for port in ports:
                    if port.channel in ready:
                        heard = self._take(port) or heard
            if heard:
                return
        now = _monotonic()
        for port in ports:
            if not port.finished and now - port.last_heard >= self.hang_after_s:
                port.gone = "hung"
                self.drop(port, "hung")

    def _take(self, port: BrickPort) -> bool:
        """Queue one message of the brick's if one has arrived; True if something happened."""
        try:
            message = port.channel.pending()
        except BAD_MESSAGE as err:
            self.drop(port, _why(err))
            return True
        if message is None:
            return False
        try:
            port.accept(message)
        except BAD_MESSAGE as err:
            self.drop(port, f"protocol: {err}")
        port.last_heard = _monotonic()
        return True
