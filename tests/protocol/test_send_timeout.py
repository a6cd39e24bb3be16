"""A socket's send timeout, in the form each system takes it."""

from __future__ import annotations

import socket
import struct

import pytest

from ev3sim2d.protocol.stream import send_timeout


class WindowsSocket:
    """What Windows' setsockopt takes for SO_SNDTIMEO: a DWORD of milliseconds (an int)."""

    def __init__(self) -> None:
        self.set: list = []

    def setsockopt(self, level, name, value) -> None:
        if not isinstance(value, int):
            raise OSError(10022, "An invalid argument was supplied")
        self.set.append((level, name, value))


def test_windows_gets_its_send_timeout_in_milliseconds():
    sock = WindowsSocket()
    send_timeout(sock, 10.0)
    assert sock.set == [(socket.SOL_SOCKET, socket.SO_SNDTIMEO, 10_000)]


@pytest.mark.skipif(not hasattr(socket, "AF_UNIX"), reason="a POSIX system's socket")
def test_posix_gets_its_send_timeout_as_a_timeval():
    """Linux and macOS refuse the short form: the timeval goes in, whole seconds and microseconds."""
    with socket.socket() as sock:
        send_timeout(sock, 2.5)
        seconds, microseconds = struct.unpack(
            "ll", sock.getsockopt(socket.SOL_SOCKET, socket.SO_SNDTIMEO, 16)
        )
    assert (seconds, microseconds) == (2, 500_000)
