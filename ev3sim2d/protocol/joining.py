"""Joining a world over TCP: the messages before and after a brick's own protocol (docs/network.md).

`ev3sim2d join` runs a brick on its own computer and connects it to a world that
`ev3sim2d serve` holds.  On the TCP connection, before the brick's messages:

    join -> serve   ["join", {protocol, token, robot, name, program, path}]
    serve -> join   ["seat", {protocol, robot, number, robots, world, tick_us, seed, limits}]
                or  ["refused", why]                      and the connection is closed

then the brick protocol (messages.py) as it is, the joining side adding what only
it knows to the welcome (the program's path, its folders, the sandbox), and at
the end of the run, before the connection is closed:

    serve -> join   ["over", {status, reason, sim_time_s, robot}]

Everything the joining side says is checked here, on the serving side, before
anything else reads it: a join message is small, and its fields have their types.
"""

from __future__ import annotations

from .messages import PROTOCOL, ProtocolError

MAX_JOIN_BYTES = 4096  # a join message is a few short texts
JOIN_TEXTS = {"token": 200, "name": 60, "program": 300, "path": 1000}


def join_message(token: str | None, robot: int | None, name: str, program: str, path: str) -> list:
    """What `join` says first: who it is, which robot it wants (1, 2, ...; None: any free one)."""
    return [
        "join",
        {
            "protocol": PROTOCOL,
            "token": token,
            "robot": robot,
            "name": name,
            "program": program,
            "path": path,
        },
    ]


def check_join(message: list) -> dict:
    """The join message's fields, checked; ProtocolError for anything else."""
    if len(message) != 2 or message[0] != "join" or type(message[1]) is not dict:
        raise ProtocolError(f"expected a join message, got {str(message[0])[:40]!r}")
    fields = message[1]
    if fields.get("protocol") != PROTOCOL:
        raise ProtocolError(
            f"protocol version {fields.get('protocol')!r}, this world speaks {PROTOCOL}: "
            "use the same ev3sim2d version on both computers"
        )
    clean: dict = {}
    for key, limit in JOIN_TEXTS.items():
        value = fields.get(key)
        if value is None and key == "token":
            clean[key] = None
            continue
        if type(value) is not str or len(value) > limit:
            raise ProtocolError(f"the join message's {key!r} must be a text of at most {limit} characters")
        clean[key] = value
    robot = fields.get("robot")
    if robot is not None and (type(robot) is not int or not 1 <= robot <= 1000):
        raise ProtocolError("the join message's 'robot' must be a robot number (1, 2, ...) or null")
    clean["robot"] = robot
    for key in ("name", "program"):  # shown on the teacher's terminal: no escape sequences
        clean[key] = "".join(ch for ch in clean[key] if ch.isprintable()).strip() or "?"
    return clean


def check_seat(message: list) -> dict:
    """What `serve` answered: the seat's fields; ProtocolError with the world's reason if it refused."""
    if len(message) == 2 and message[0] == "refused" and type(message[1]) is str:
        raise JoinRefused(message[1][:500])
    if len(message) != 2 or message[0] != "seat" or type(message[1]) is not dict:
        raise ProtocolError("the other side does not speak ev3sim2d's protocol (no seat, no refusal)")
    seat = message[1]
    if seat.get("protocol") != PROTOCOL:
        raise ProtocolError(
            f"the world speaks protocol version {seat.get('protocol')!r}, this ev3sim2d {PROTOCOL}: "
            "use the same ev3sim2d version on both computers"
        )
    for key, kind in (("robot", str), ("number", int), ("robots", int), ("tick_us", int), ("seed", int)):
        if type(seat.get(key)) is not kind:
            raise ProtocolError(f"the world's seat message has no valid {key!r}")
    if type(seat.get("limits")) is not dict:
        raise ProtocolError("the world's seat message has no limits")
    return seat


class JoinRefused(ProtocolError):
    """The world would not seat this brick (full, wrong token, robot taken): the message says why."""
