"""Bricks and the world in lockstep over virtual time: the simulator's turn-taking.

Each brick runs ahead on its own clock and says when it passes a tick (a tick
marker).  The world steps to a tick only once every brick still running has
passed it (conservative lockstep, as in parallel discrete-event simulation),
and the bricks waiting there get their snapshot.  A brick in a quiet wait (op "u":
it waits for a value of its robot to change) is not waited for: the world runs on,
taking its snapshot each tick as for any brick, and stops at the tick where the
value changed, where the brick goes on (BrickPort.wakes).  Between ticks a brick's ops
touch only its own robot's devices, so the bricks' ops between two ticks can
be applied brick by brick: the run depends only on what the programs do, never
on which process was faster.  The simulator never waits for a brick that is
ahead; a brick that is behind and whose clock does not move for `hang_after_s`
of real time that the simulator spent waiting for it or applying its ops is
stopped as hung: a program waiting on something outside the simulation (a
real lock, a pipe), computing inside one long call of compiled code, or one
that sends heartbeats, lines or calls that do not move its clock.  (A program
that computes in Python, even in a loop that never uses the robot or the
clock, moves its clock: its lines cost time on the brick, so it runs on to
the time limit.)  The time a brick waits for the world, or for the simulator
busy with other bricks, is never held against it.  A brick stopped at the time
limit or as hung answers the stop with its end message, which says where each
thread of its program was: the session waits a little for it (`where`).  What
a brick sends is applied in one place (`_apply`), where whatever goes wrong
ends that brick only: a breach of the protocol, a budget (results/trace.py), or
the simulator's own failure on its ops, which is reported loudly.  A robot whose
program ended (or whose brick was dropped) while others run on is let go, as an
EV3's brickman does when a program ends: its motors are reset (Simulation.let_go).
"""

from __future__ import annotations

import gc
import os
import sys
import time
import traceback
from collections.abc import Callable

from ..protocol import ConnectionGone, ProtocolError, wait_for_any
from ..protocol.stream import cores_idle
from .brick_port import BrickPort, OverBudget, said_threads
from .mailboxes import Mailboxes
from .simulation import Simulation

_perf_counter = time.perf_counter
_yield = getattr(os, "sched_yield", lambda: None)
SPIN_S = 0.002
LAST_WORDS_S = 1.0  # real seconds to wait, at most, for the bricks stopped to say where their programs were


def _why(err: Exception) -> str:
    """Why a brick ends for what it sent: gone, a breach of the protocol, a budget."""
    if isinstance(err, ConnectionGone):
        return f"gone: {err}"
    if isinstance(err, OverBudget):
        return f"budget: {err}"
    return f"protocol: {err}"


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
        self._stopped: list[BrickPort] = []  # bricks stopped at the time limit or as hung, to hear from
        self.where: dict[int, list] = {}  # robot index -> [thread, file, line] of its program's threads
        for port in ports:
            port.time_limit_us = limit_us
        Mailboxes(ports, sim.tick_us)  # (Bluetooth between these bricks: port.mailboxes)

    def set_spin(self, spin: bool) -> None:
        """Whether the simulator and its bricks spin as they wait for each other from now on (a live run
        as fast as it goes), or sleep until woken (a live run at the pace of the clock, which mostly waits
        for the clock: spinning would only burn the cores)."""
        self.spin_s = SPIN_S if spin else 0.0
        for port in self.ports:
            port.channel.set_spin(self.spin_s)

    def _step_to(self, target_us: int) -> int:
        """Run the world's ticks up to target_us; after each, the snapshots bricks will need.  A quiet brick
        that wakes at a tick (its value changed) stops the world there: returns where the world is."""
        tick = self.sim.tick
        step = self.sim.tick_us
        while self.next_tick_us <= target_us:
            now = self.next_tick_us
            tick(now)
            self.next_tick_us += step
            self.world_us = now
            woke = self._snapshots(now)
            if woke is not None and woke < target_us:
                target_us = woke
        self.world_us = target_us
        if self.printed:
            self._echo(target_us)
        return target_us

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

    def _snapshots(self, tick_us: int) -> int | None:
        """After the tick at tick_us: a brick in [tick_us, +tick) will read from this snapshot next tick;
        one that jumped to tick_us + tick (a sleep) needs it at once.  Always taken, sent or not, so that
        the record never depends on which process was faster.  A quiet brick's is taken each tick too,
        and sent only if it wakes it (BrickPort.wakes): returns that tick, if one woke."""
        label = tick_us + self.sim.tick_us
        woke = None
        for port in self.ports:
            if port.finished:
                continue
            if port.quiet is not None:
                if self._apply(port, lambda port=port: port.wakes(label)):
                    woke = label
            elif port.declared in (tick_us, label):
                self._apply(port, port.snapshot, label)
        return woke

    def drop(self, port: BrickPort, why: str) -> None:
        """End a brick's part in the run (it broke the protocol or a budget, went away, or hung)."""
        if not port.finished:
            port.gone = why
        if why in ("hung", "time limit") and port not in self._stopped:
            self._stopped.append(port)
        port.send(["stop", why])

    def _hear_where(self) -> None:
        """The bricks stopped at the time limit or as hung answer the stop with their end message, which
        says where each of the program's threads was (docs/protocol.md): wait for it, LAST_WORDS_S at
        most in all.  What else they send now is not applied: their run is over."""
        waiting = [port for port in self._stopped if not port.broken]
        self._stopped = []
        deadline = _perf_counter() + LAST_WORDS_S
        while waiting:
            left = deadline - _perf_counter()
            if left <= 0:
                return
            for port in list(waiting):
                try:
                    message = port.channel.receive(timeout_s=min(left, 0.05) / len(waiting))
                except ProtocolError:
                    waiting.remove(port)
                    continue
                if message is not None and message[0] == "end" and len(message) == 2:
                    waiting.remove(port)
                    threads = said_threads(message[1])
                    if threads:
                        self.where[port.index] = threads

    def _apply(self, port: BrickPort, work: Callable[..., object], *args):
        """Do `work` on this brick's behalf (take its messages, apply its ops, take its snapshot): the one
        place where what a brick sends reaches the world.  Whatever goes wrong ends this brick only, and
        the run goes on for the others: a message that is not the protocol, a budget it went past, its
        connection gone, and any other exception, which is the simulator's own failure on this brick's
        ops (our bug, or a value nobody foresaw): said on stderr with its traceback, and in the reason.
        Returns what `work(*args)` returns, None once the brick is dropped."""
        try:
            return work(*args)
        except (ProtocolError, OverBudget) as err:
            self.drop(port, _why(err))
        except Exception as err:  # noqa: BLE001 - contained to this brick, and reported loudly
            what = f"{type(err).__name__}: {str(err)[:500]}"
            print(
                f"ev3sim2d: the simulator failed applying robot {port.index + 1}'s ops (a bug in ev3sim2d, "
                f"please report it); that robot's run ends, the others run on:\n{traceback.format_exc()}",
                file=sys.stderr,
                flush=True,
            )
            self.drop(port, f"simulator failure: applying this brick's ops raised {what} (a bug in ev3sim2d)")
        return None

    def _stalled(self, port: BrickPort, clock_us: int, spent_s: float, judge: bool = True) -> None:
        """The simulator spent spent_s of real time on this brick (waiting for it, or applying its ops): held
        against it unless its clock moved past clock_us.  Judged (judge: its messages so far are applied),
        a brick whose clock has stood still for hang_after_s of such time is stopped as hung."""
        if port.time_us > clock_us or port.debugged:  # (a program stopped in its debugger is not hung)
            port.debugged = False
            port.stalled_s = 0.0
            return
        port.stalled_s += spent_s
        if judge and port.stalled_s >= self.hang_after_s and not port.finished:
            self.drop(port, "hung")

    def _drain(self, port: BrickPort) -> None:
        """Apply whatever the brick has sent, as far as the world's time allows; the real time it takes is
        held against the brick while its clock stands still (judged once what it read is applied)."""
        if not port.finished:
            self._apply(port, self._drain_now, port)

    def _drain_now(self, port: BrickPort) -> None:
        """_drain's work, in one _apply: whatever it raises ends this brick (a step that raises would end
        it just as well, and the next would not run), at one call a tick instead of four."""
        started, clock = _perf_counter(), port.time_us
        pending, run_ops, accept = port.channel.pending, port.run_ops, port.accept
        while True:
            run_ops(self.world_us)
            if port.finished or port.marker is not None:
                return
            now = _perf_counter()
            self._stalled(port, clock, now - started)
            if port.finished:
                return
            started, clock = now, port.time_us
            message = pending()
            if message is None:
                if port.broken:
                    self.drop(port, "gone: the brick closed the connection")
                return
            accept(message)

    def run(self) -> None:
        self._restart_hang_clocks()
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

    def _restart_hang_clocks(self) -> None:
        for port in self.ports:
            port.stalled_s = 0.0

    def finish(self) -> None:
        """The world to the moment the last brick ended (or the time limit), and every printed line shown;
        where the programs stopped were."""
        if not self.interrupted:
            self._hear_where()
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
        self._restart_hang_clocks()
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
        while not port.finished:
            self._drain(port)
            if port.finished:
                return
            target = port.marker
            if target is None:
                self._wait([port])
                continue
            if limit is not None and target >= limit:
                if self._stop_at_limit([port]):
                    return
                target = self.world_us
            if self._paused_before(target):
                return
            self._step_to(target)
            port.marker = None
            port.stalled_s = 0.0  # (it waited for the world: not its own time)

    def _stop_at_limit(self, live: list[BrickPort]) -> bool:
        """Every brick still running has passed the time limit: the world runs to it, and the run ends
        (True); unless a quiet brick wakes before it (False: the world is where it woke, a tick its marker
        is at)."""
        if self._step_to(self.limit_us) < self.limit_us:
            return False
        for port in live:
            port.time_us = self.limit_us
            port.end = {"t_us": self.limit_us, "status": "time_limit", "error": None}
            self.drop(port, "time limit")
        return True

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
                    if self._stop_at_limit(live):
                        return
                    target = self.world_us
                if self._paused_before(target):
                    return
                target = self._step_to(target)
                for port in live:
                    if port.marker == target:
                        port.marker = None
                        port.stalled_s = 0.0  # (it waited for the world: not its own time)
                continue
            self._wait(behind)

    def _wait(self, ports: list[BrickPort]) -> None:
        """Wait until one of these bricks (all behind the world) says something.  The time waited is held
        against each of them (_stalled): one that said nothing is stopped once its clock has stood still
        for too long; one that did is judged once what it said is applied."""
        started = _perf_counter()
        clocks = [port.time_us for port in ports]
        left = max(0.0, min(self.hang_after_s - port.stalled_s for port in ports))
        heard: set[int] = set()
        if len(ports) == 1:
            port = ports[0]
            message = self._apply(port, lambda: port.channel.receive(timeout_s=left))
            if message is not None:
                heard.add(port.index)
                self._apply(port, lambda: port.accept(message))
        else:
            spin_end = _perf_counter() + (self.spin_s if cores_idle() else 0.0)
            while not heard:
                heard.update(port.index for port in ports if self._take(port))
                if heard or _perf_counter() > spin_end:
                    break
                _yield()  # a brick that shares this core runs now, not at the end of a time slice
            if not heard:
                channels = [p.channel for p in ports]
                try:
                    ready = wait_for_any(channels, min(0.05, left))
                except ProtocolError:
                    ready = [c for c in channels if c.closed]
                heard.update(port.index for port in ports if port.channel in ready and self._take(port))
        spent = _perf_counter() - started
        for port, clock in zip(ports, clocks, strict=True):
            if not port.finished:
                self._stalled(port, clock, spent, judge=port.index not in heard)

    def _take(self, port: BrickPort) -> bool:
        """Queue one message of the brick's if one has arrived; True if something happened."""
        if port.finished:
            return False
        message = self._apply(port, port.channel.pending)
        if message is None:
            return port.finished
        self._apply(port, lambda: port.accept(message))
        return True
