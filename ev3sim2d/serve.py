"""One run whose bricks join over TCP: the world of `ev3sim2d serve` (docs/network.md).

The world, its robots, the session and the result are those of `run` (run.py);
only the bricks differ: each runs on the computer of whoever joined (join.py),
and its connection is a TCP socket the lobby seated (lobby.py).  Lockstep over
virtual time (session.py) makes a slow or distant brick change the wall time
only: the same programs give the same run as `ev3sim2d run`, fingerprint for
fingerprint.  A brick that goes away, stalls or breaks the protocol is dropped
and its robot is left as after any program that ended (Simulation.let_go); the
others run on.  At the end each brick still connected is told how the run ended.
"""

from __future__ import annotations

import gc
import socket
from collections.abc import Sequence

from .protocol import ProtocolError
from .protocol.stream import send_timeout
from .simulator.brick_port import BrickPort
from .simulator.bricks import BrickLimits
from .simulator.lobby import Guest, Lobby
from .simulator.run import RunResult, new_simulation, play, robot_names, run_result, take_hello
from .world.robot_spec import RobotSpec
from .world.world import World


def serve_run(
    lobby: Lobby,
    world: World,
    count: int,
    robot: RobotSpec | Sequence[RobotSpec | None] | None = None,
    time_limit_s: float | None = 60.0,
    seed: int = 0,
    hang_after_s: float = 5.0,
    echo=None,
    presses: list | None = None,
    limits: BrickLimits | None = None,
) -> tuple[RunResult, list[Guest]]:
    """Wait until `count` bricks joined through the (open) lobby, run them, tell them how it ended.

    The arguments mean what they mean for run_programs; KeyboardInterrupt while waiting ends with no run.
    """
    sim, presses = new_simulation(world, count, robot, seed, presses)
    names = robot_names(count)
    limits = limits or BrickLimits()
    limit_us = None if time_limit_s is None else int(round(time_limit_s * 1e6))
    tick_us = sim.tick_us

    def seat(i: int) -> dict:
        return {
            "robot": names[i],
            "number": i + 1,
            "robots": count,
            "world": world.name,
            "tick_us": tick_us,
            "seed": seed,
            "limits": {
                "cpu_s": limits.cpu_s,
                "memory_mb": limits.memory_mb,
                "file_mb": limits.file_mb,
                "processes": limits.processes,
            },
        }

    guests = lobby.fill(seat)
    lobby.refuse_during_run()
    printed: list = []
    ports = []
    for i, guest in enumerate(guests):
        port = BrickPort(i, sim.robots[i], guest.channel, sim.trace, presses, printed)
        take_hello(port, guest.greeting)
        try:
            for message in guest.early:
                port.accept(message)
        except ProtocolError as err:
            port.gone = f"protocol: {err}"
            port.send(["stop", port.gone])
        ports.append(port)
    session, wall = play(sim, ports, limit_us, hang_after_s, printed, echo)
    shown = [(g.fields["program"], g.fields["path"]) for g in guests]
    result = run_result(sim, shown, ports, [None] * count, wall, session)
    for guest, port, own in zip(guests, ports, result.robots, strict=True):
        _tell_over(guest, port, result, own)
    del sim, ports, session
    gc.collect()  # free the pymunk world now: left to interpreter exit, its teardown complains
    return result, guests


def _tell_over(guest: Guest, port: BrickPort, result: RunResult, own: dict) -> None:
    """The run is over: how it ended, for the whole world and for this brick's robot; then close."""
    over = {"status": result.status, "reason": result.reason, "sim_time_s": result.sim_time_s, "robot": own}
    try:
        send_timeout(guest.sock, 2.0)
        guest.channel.send(["over", over])
        guest.sock.shutdown(socket.SHUT_WR)
    except (ProtocolError, OSError):
        pass
