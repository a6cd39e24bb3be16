"""The brick protocol: the messages a brick process and the simulator exchange, and their framing.

Shared by both sides; imports nothing else of ev3sim2d.  docs/protocol.md is written from it.
"""

from .messages import PROTOCOL, ConnectionGone, ProtocolError, decode, encode
from .shared_memory import SharedChannel
from .stream import Channel, wait_for_any

__all__ = [
    "PROTOCOL",
    "ConnectionGone",
    "ProtocolError",
    "Channel",
    "SharedChannel",
    "decode",
    "encode",
    "wait_for_any",
]
