"""The messages of the brick protocol, version 1: one JSON array per message, its kind first.

A brick (the student's program, its threads, the ev3dev2 shim and the brick's
virtual clock) and the simulator (the world, the devices, the trace) talk in
lockstep over virtual time, counted in whole microseconds.  The brick runs
ahead on its own clock; it tells the simulator what it did, in order, and asks
only when it needs an answer.  See docs/protocol.md for the full description.

Simulator -> brick
    ["welcome", {config}]             once, first: protocol, robot, tick_us, limit_us, seed, program...
    ["snap", tick_us, [values]]       the subscribed attributes' values once the world reached tick_us
    ["reply", [answers], [values]]    answers to a batch's requests, and every subscribed value now
    ["stop", reason]                  the run is over (the simulator ended it)

Brick -> simulator
    ["hello", {info}]                 once, first: protocol, sandbox report
    ["ops", [op, ...]]                what the program did, in order (below)
    ["end", {how}]                    the program ended: t_us, status, error

Ops (inside "ops")
    ["k", key, class, device, attribute]   names an attribute: later ops use the integer key
    ["w", key, value]                      write (value: text); ["w", key, value, t_us] when its time matters
    ["t", tick_us]                         the brick's clock passed this tick: the world may step to it
    ["r", key]                             read (answered in the reply; subscribes the key to snapshots)
    ["c", t_us, feature, [args]]           a brick feature (sound, display, buttons, devices), answered
    ["p", t_us, stream, text]              a printed line
    ["q"]                                  end of a batch that wants a reply

Values are text; a read that fails is [errno, message] instead.  An answer to a
call is any JSON value, or {"error": [kind, message]}.
"""

from __future__ import annotations

import json

PROTOCOL = 1
MAX_MESSAGE_BYTES = 8 * 2**20  # one message; a brick that sends more is cut off

_dumps = json.JSONEncoder(ensure_ascii=False, separators=(",", ":"), check_circular=False).encode
_loads = json.loads


class ProtocolError(Exception):
    """The other side sent something that is not this protocol (or went away)."""


def encode(message: list) -> bytes:
    """One message as one line of UTF-8 JSON."""
    return _dumps(message).encode("utf-8", "surrogatepass") + b"\n"


def decode(line: bytes) -> list:
    """One line back into a message; ProtocolError for anything that is not a JSON array led by a kind."""
    try:
        message = _loads(line)
    except (ValueError, RecursionError) as err:
        raise ProtocolError(f"not a JSON message ({err})") from None
    if type(message) is not list or not message or type(message[0]) is not str:
        raise ProtocolError("a message must be a JSON array whose first item is its kind")
    return message
