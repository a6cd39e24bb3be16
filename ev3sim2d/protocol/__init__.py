"""The brick protocol: the messages a brick process and the simulator exchange, and their framing.

Shared by both sides; imports nothing else of ev3sim2d.  docs/protocol.md is written from it.
"""

from .messages import PROTOCOL, ProtocolError, decode, encode
from .stream import Channel

__all__ = ["PROTOCOL", "ProtocolError", "Channel", "decode", "encode"]
