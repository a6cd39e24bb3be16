"""A brick on this computer for a world on another: the joining side of `ev3sim2d join` (docs/network.md).

It connects to the world over TCP, says who it is (protocol/joining.py) and is
given a robot; it then starts a brick process here, sandboxed as for `run`
(simulator/bricks.py), and passes the brick's messages on, both ways, unchanged,
showing the program's printed lines as they come.  It ends when the world says
the run is over, or when the world goes away.  The world trusts nothing it
says: everything arriving over the connection is checked there as a brick's
messages always are.
"""

from __future__ import annotations

import os
import socket
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from .protocol import Channel, ConnectionGone, ProtocolError, wait_for_any
from .protocol.joining import JoinRefused, check_seat, join_message
from .simulator.bricks import BrickLimits, BrickProcess, brick_welcome, start_brick
from .simulator.program import Program

CONNECT_TIMEOUT_S = 10.0
SEAT_TIMEOUT_S = 30.0


class JoinError(Exception):
    """This brick could not join the world (no world there, refused, not ev3sim2d): the message says why."""


@dataclass
class JoinResult:
    """How the run ended, as the world said (over: None if the world went away first)."""

    seat: dict
    over: dict | None
    local_end: dict | None  # the brick's own end message
    lost: str | None = None  # why the connection to the world ended before the run did


def parse_address(text: str) -> tuple[str, int]:
    """HOST:PORT (an IPv6 host in brackets: [::1]:PORT) as host and port; ValueError saying the form."""
    host, sep, port = text.rpartition(":")
    host = host[1:-1] if host.startswith("[") and host.endswith("]") else host
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"{text!r}: give the world's address as HOST:PORT, e.g. 127.0.0.1:9003")
    return host, int(port)


def connect(address: str, timeout_s: float = CONNECT_TIMEOUT_S, wait_s: float = 0.0) -> socket.socket:
    """A TCP connection to the world; wait_s: how long to keep trying while nothing listens there yet
    (students who start before their teacher serves)."""
    host, port = parse_address(address)
    give_up = time.monotonic() + wait_s
    while True:
        try:
            return _connect(host, port, timeout_s)
        except JoinError as err:
            if not err.args[0].startswith("no world is served") or time.monotonic() >= give_up:
                raise
            time.sleep(0.2)


def _connect(host: str, port: int, timeout_s: float) -> socket.socket:
    try:
        sock = socket.create_connection((host, port), timeout=timeout_s)
    except ConnectionRefusedError:
        raise JoinError(
            f"no world is served at {host}:{port} (connection refused): is `ev3sim2d serve` running there, "
            "on this port?"
        ) from None
    except socket.gaierror as err:
        raise JoinError(f"{host}: no such computer ({err.strerror})") from None
    except TimeoutError:
        raise JoinError(f"{host}:{port} did not answer within {timeout_s:g} s") from None
    except OSError as err:
        raise JoinError(f"could not connect to {host}:{port}: {err.strerror or err}") from None
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    sock.settimeout(None)
    return sock


def take_seat(
    sock: socket.socket, token: str | None, robot: int | None, name: str, program: Path, shown: str
) -> tuple[Channel, dict]:
    """Say who this brick is; the world's seat (its robot, clock, seed, limits), or JoinError why not."""
    channel = Channel(sock)
    try:
        channel.send(join_message(token, robot, name, shown, str(program)))
        answer = channel.receive(timeout_s=SEAT_TIMEOUT_S)
        if answer is None:
            raise JoinError(f"the world did not answer within {SEAT_TIMEOUT_S:g} s")
        return channel, check_seat(answer)
    except JoinRefused as err:
        raise JoinError(f"the world refused this brick: {err}") from None
    except ConnectionGone:
        raise JoinError("the world closed the connection without a word (is it an ev3sim2d world?)") from None
    except ProtocolError as err:
        raise JoinError(f"the other side does not speak ev3sim2d's protocol ({err})") from None


def _limits(seat: dict) -> BrickLimits:
    """The world's limits for the brick, never above this computer's defaults."""
    mine = BrickLimits()
    given = seat["limits"]

    def pick(key: str) -> int:
        value = given.get(key)
        ours = getattr(mine, key)
        return min(value, ours) if type(value) is int and value > 0 else ours

    return BrickLimits(pick("cpu_s"), pick("memory_mb"), pick("file_mb"), pick("processes"))


def run_joined(
    address: str,
    program_file: str | Path,
    robot: int | None = None,
    name: str | None = None,
    token: str | None = None,
    echo: Callable[[float, str, str], None] | None = None,
    log: Callable[[str], None] = lambda text: None,
    wait_s: float = 0.0,
) -> JoinResult:
    """Join the world at address with the program, run it in a brick here until the run is over.

    echo(t_s, stream, text) shows each printed line as it comes; log(text) says what happens; wait_s: how
    long to keep trying to connect while no world is served there yet."""
    program = Program(program_file)  # ProgramError: the caller reports it (nothing is sent)
    path = program.path.resolve()
    sock = connect(address, wait_s=wait_s)
    try:
        net, seat = take_seat(sock, token, robot, name or path.stem, path, str(program_file))
    except BaseException:
        sock.close()
        raise
    log(
        f"joined '{seat.get('world', '?')}' as robot {seat['number']} of {seat['robots']}; "
        "the run starts when every robot has a program"
    )
    limits = _limits(seat)
    brick, read_paths = start_brick([path.parent], limits=limits, program=path)
    try:
        brick.channel.send(
            brick_welcome(brick, read_paths, path, seat["robot"], seat["tick_us"], seat["seed"], limits)
        )
        return _relay(brick, net, seat, echo, path)
    finally:
        brick.stop(patience_s=2.0)
        net.close()


def _relay(brick: BrickProcess, net: Channel, seat: dict, echo, program: Path) -> JoinResult:
    """Pass messages both ways until the world says the run is over (or is gone).  The brick's error
    names the program's folder as it is here, not the copy its brick worked in."""
    local = brick.channel
    result = JoinResult(seat, None, None)
    brick_on = True
    while True:
        wait_for_any([local, net] if brick_on else [net], 1.0)
        if brick_on:
            try:
                while (message := local.pending()) is not None:
                    message = _named_as_here(message, brick, program)
                    _show(message, result, echo)
                    if not _forward(net, message, result):
                        return result
            except ProtocolError:  # the brick ended (or broke its side of the protocol: the world will see)
                brick_on = False
                try:
                    net.sock.shutdown(socket.SHUT_WR)  # the world reads the end; it still tells us "over"
                except OSError:
                    pass
        try:
            while (message := net.pending()) is not None:
                if message[0] == "over" and len(message) == 2 and type(message[1]) is dict:
                    result.over = message[1]
                    return result
                if brick_on:
                    try:
                        local.send(message)
                    except ProtocolError:
                        brick_on = False
        except ConnectionGone:
            result.lost = "the world closed the connection"
            return result
        except ProtocolError as err:
            result.lost = f"the world sent something that is not ev3sim2d's protocol ({err})"
            return result


def _named_as_here(message: list, brick: BrickProcess, program: Path) -> list:
    """The brick's end message with its error's file names as they are on this computer."""
    error = (
        message[1].get("error")
        if message[0] == "end" and len(message) == 2 and type(message[1]) is dict
        else None
    )
    if brick.working is None or type(error) is not dict:
        return message
    copy, original = os.path.join(str(brick.working.folder), ""), os.path.join(str(program.parent), "")
    named = {k: v.replace(copy, original) if type(v) is str else v for k, v in error.items()}
    return ["end", {**message[1], "error": named}]


def _forward(net: Channel, message: list, result: JoinResult) -> bool:
    try:
        net.send(message)
        return True
    except ProtocolError:
        result.lost = "the connection to the world is gone"
        return False


def _show(message: list, result: JoinResult, echo) -> None:
    """Printed lines as they come (as the brick sent them: echo, the front door's, shows them safely on a
    terminal, and passes on only a line that is text with a time); the brick's end message, for the report."""
    kind = message[0]
    if kind == "ops" and echo is not None and len(message) == 2 and type(message[1]) is list:
        for op in message[1]:
            printed = type(op) is list and len(op) == 4 and op[0] == "p"
            if printed and type(op[1]) is int and type(op[3]) is str:
                echo(op[1] / 1e6, "stderr" if op[2] == "stderr" else "stdout", op[3])
    elif kind == "end" and len(message) == 2 and type(message[1]) is dict:
        result.local_end = message[1]
