"""A brick on this computer over loopback TCP, where a socket pair cannot be handed to a new process.

Windows cannot pass a socket to a child as an inherited fd (nor can a system without fork and
pass_fds), so there the simulator listens on 127.0.0.1, on a port the system picks, and starts the
brick with a one-time token on its standard input (which, unlike its command line, no other program
on the computer can read).  The brick connects and says the token first:

    brick -> simulator   ["brick", {"token": T}]

then speaks the brick protocol (messages.py) as over a socket pair.  The simulator takes the first
connection that says the right token within the time it gives the brick to start (compared in
constant time); any other connection (another program on this computer that found the port, one
that says nothing, or a wrong token) is closed, and it waits on.  Where the system lets another
program bind the same port (Windows' SO_REUSEADDR), the port is bound exclusively.
"""

from __future__ import annotations

import hmac
import secrets
import socket
import time

from .messages import ProtocolError
from .stream import Channel

HOST = "127.0.0.1"
HELLO_TIMEOUT_S = 5.0  # a connection must say its token within this much real time
MAX_TOKEN = 200


class LoopbackListener:
    """The simulator's end before a brick connects: a listening socket and the token it expects."""

    def __init__(self) -> None:
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        exclusive = getattr(socket, "SO_EXCLUSIVEADDRUSE", None)
        if exclusive is not None:
            self.sock.setsockopt(socket.SOL_SOCKET, exclusive, 1)
        self.sock.bind((HOST, 0))
        self.sock.listen(8)
        self.token = secrets.token_hex(16)

    @property
    def port(self) -> int:
        return self.sock.getsockname()[1]

    def accept(self, timeout_s: float, still_starting=lambda: True, spin_s: float = 0.0) -> Channel | None:
        """The brick's connection, once it said the token; None when timeout_s passes first or
        still_starting() says the brick is gone."""
        deadline = time.monotonic() + timeout_s
        while still_starting():
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            self.sock.settimeout(min(left, 0.25))
            try:
                conn, _ = self.sock.accept()
            except TimeoutError:
                continue
            conn.settimeout(None)
            channel = Channel(conn, spin_s=spin_s)
            if self._says_token(channel, min(HELLO_TIMEOUT_S, max(0.1, deadline - time.monotonic()))):
                conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                return channel
            channel.close()
        return None

    def _says_token(self, channel: Channel, timeout_s: float) -> bool:
        try:
            message = channel.receive(timeout_s=timeout_s)
        except ProtocolError:
            return False
        if not message or message[0] != "brick" or len(message) != 2 or type(message[1]) is not dict:
            return False
        token = message[1].get("token")
        if type(token) is not str or len(token) > MAX_TOKEN:
            return False
        return hmac.compare_digest(token.encode(), self.token.encode())

    def close(self) -> None:
        self.sock.close()


def connect(port: int, token: str) -> Channel:
    """The brick's end: connect to the simulator on this computer and say the token."""
    sock = socket.create_connection((HOST, port))
    sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    channel = Channel(sock)
    channel.send(["brick", {"token": token}])
    return channel
