"""The messages of the brick protocol, version 2: one JSON array per message, its kind first.

A brick (the student's program, its threads, the ev3dev2 shim and the brick's
virtual clock) and the simulator (the world, the devices, the trace) talk in
lockstep over virtual time, counted in whole microseconds.  The brick runs
ahead on its own clock; it tells the simulator what it did, in order, and asks
only when it needs an answer.  docs/protocol.md describes it in full.

Simulator -> brick
    ["welcome", {config}]             first: protocol, robot, tick_us, seed, program, sandbox
    ["snap", label_us, [values]]      the live attributes' values for the brick's reads while its clock
                                      is in [label_us, label_us + tick_us): taken after the world's tick
                                      at label_us - tick_us
    ["reply", [answers], [values]]    answers to a batch's requests, in order, and every live value now
    ["stop", reason]                  the run is over for this brick (time limit, broken rule, hang)

Brick -> simulator
    ["hello", {info}]                 first: protocol, the sandbox it got (layer -> "on" / "off: why")
    ["ops", [op, ...]]                what the program did, in order (below)
    ["end", {how}]                    the program ended: t_us, status, error

Ops (inside "ops")
    ["k", key, class, device, attribute]   names an attribute; keys are 0, 1, 2, ... in order
    ["w", key, value]                      write, checked by the brick against the attribute's rule;
                                           ["w", key, value, t_us] when its time is recorded (LEDs)
    ["W", key, value]                      write, answered [error or null, the attribute's write rule]
    ["t", tick_us]                         the brick's clock passed this tick (the last of several)
    ["u", first, last, key, value]         a quiet wait (version 2): the clock passes the ticks first,
                                           first + tick, ... last while the live key's value in each
                                           tick's snapshot is `value`; the simulator sends only the
                                           snapshot of the tick where it is not (or of last): the brick
                                           is there.  first's snapshot was sent already (the brick looks)
    ["R", key]                             read, answered [kind, value]; kind "constant", "setting"
                                           (changes only when the program writes the device) or
                                           "live" (from now on in every snapshot and reply)
    ["c", t_us, feature, [args]]           a brick feature (sound, display), not answered
    ["C", t_us, feature, [args]]           a brick feature (buttons, devices, volume), answered
    ["p", t_us, stream, text]              a printed line
    ["@", t_us]                            the clock moves between ticks (at most every 0.5 s of real time)
    ["q"]                                  end of a batch that wants a reply

Values are text; a read that fails is [errno, message] instead.  A write rule is
["int", low, high] (null: no bound), ["choice", [texts]], ["any"] or null (ask
every time).  An answer to a call is any JSON value, or {"error": [kind, message]}.
"""

from __future__ import annotations

import json

PROTOCOL = 2
MAX_MESSAGE_BYTES = 8 * 2**20  # one message; a brick that sends more is cut off

_encoder = json.JSONEncoder(ensure_ascii=False, separators=(",", ":"), check_circular=False)
_scan = json.JSONDecoder().scan_once
try:  # the C encoder made once, not per message as JSONEncoder.encode does: half the time of a message
    from json.encoder import c_make_encoder, encode_basestring

    _iterencode = c_make_encoder(
        None, _encoder.default, encode_basestring, None, ":", ",", False, False, True
    )
except (ImportError, TypeError):  # pragma: no cover - a Python without the _json accelerator
    _iterencode = None


def _dumps(message: list) -> str:
    if _iterencode is None:  # pragma: no cover
        return _encoder.encode(message)
    return "".join(_iterencode(message, 0))


class ProtocolError(Exception):
    """The other side sent something that is not this protocol (or went away)."""


class ConnectionGone(ProtocolError):
    """The other side closed the connection, or its process ended."""


def encode(message: list) -> bytes:
    """One message as one line of UTF-8 JSON."""
    return _dumps(message).encode("utf-8", "surrogatepass") + b"\n"


def decode(line: bytes) -> list:
    """One line back into a message; ProtocolError for anything that is not a JSON array led by a kind."""
    try:
        text = line.decode("utf-8", "surrogatepass")  # (as encode writes a lone surrogate: a file name's)
        try:  # the scanner alone: json.loads adds two regular expressions and three calls
            message, end = _scan(text, 0)
        except StopIteration:
            end = -1
        if end != len(text):
            message = json.loads(text)  # spaces around the array (or not JSON: the error says where)
    except (ValueError, RecursionError) as err:  # UnicodeDecodeError is a ValueError
        raise ProtocolError(f"not a JSON message ({err})") from None
    if type(message) is not list or not message or type(message[0]) is not str:
        raise ProtocolError("a message must be a JSON array whose first item is its kind")
    return message
