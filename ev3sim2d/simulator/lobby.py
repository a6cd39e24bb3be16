"""Seats for bricks on other computers: the TCP side of `ev3sim2d serve` (docs/network.md).

A world for N robots listens on a TCP port.  Each connection must say who it is
(protocol/joining.py) within JOIN_TIMEOUT_S, with the world's token if it has one;
it is given the robot it asked for, or the first free one, with what its brick's
welcome needs, and its brick must greet (hello) within START_TIMEOUT_S.  A
connection that does not speak the protocol, stalls, brings a wrong token, asks for
a robot that is taken, or comes when every robot has a program is told why (when it
can be) and closed; one that goes away before the start frees its robot.  The lobby
is full when every robot's brick has greeted: from then on each connection is a
brick's channel like any other (session.py), and `refuse_during_run` turns later
comers away.
"""

from __future__ import annotations

import errno
import hmac
import select
import socket
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

from ..protocol import PROTOCOL, Channel, ConnectionGone, ProtocolError, encode
from ..protocol.joining import MAX_JOIN_BYTES, check_join
from ..protocol.stream import send_timeout

JOIN_TIMEOUT_S = 10.0  # a connection says who it is within this much time
START_TIMEOUT_S = 60.0  # its brick greets within this much time (an interpreter starting on a slow laptop)
SEND_TIMEOUT_S = 10.0  # a connection that takes no data for this long is gone
MAX_WAITING = 64  # connections that have not yet said who they are
MAX_EARLY_BYTES = 16 * 2**20  # what a brick may send before the run starts (it soon waits for the world)
LOOPBACK = ("127.0.0.1", "::1", "localhost")


class AddressInUse(OSError):
    """The port is taken (another world served here?): the message says which and what to do."""


@dataclass
class Guest:
    """One connection: who it says it is, the robot it holds (0-based; None: none yet), its first words."""

    sock: socket.socket
    channel: Channel
    address: str
    deadline: float
    fields: dict = field(default_factory=dict)  # name, program, path, robot asked for, token
    seat: int | None = None
    greeting: list | None = None  # the brick's hello (or the end of a program it could not start)
    early: list = field(default_factory=list)  # what the brick sent after hello, before the run
    finished: bool = False  # its brick ended and closed its side before the run (nothing more to read)

    @property
    def who(self) -> str:
        if not self.fields:
            return f"a connection from {self.address}"
        return f"{self.fields['name']} ({self.fields['program']}, from {self.address})"


class Lobby:
    """A listening TCP socket and the robots of one world, each waiting for a brick."""

    def __init__(self, host: str, port: int, seats: int, token: str | None, log: Callable[[str], None]):
        self.host = host
        self.port = port
        self.seats = seats
        self.token = token
        self.log = log
        self.listener: socket.socket | None = None
        self.guests: list[Guest] = []
        self._late: threading.Thread | None = None
        self._closing = False

    # ------------------------------------------------------------------ opening
    def open(self) -> tuple[str, int]:
        """Listen; the address and port (port 0 asks the system for a free one)."""
        family = socket.AF_INET6 if ":" in self.host else socket.AF_INET
        listener = socket.socket(family, socket.SOCK_STREAM)
        # POSIX: take the port at once after an earlier world's connections; Windows' SO_REUSEADDR would
        # let another program take a port in use, so there the port is bound exclusively instead
        exclusive = getattr(socket, "SO_EXCLUSIVEADDRUSE", None)
        if exclusive is not None:
            listener.setsockopt(socket.SOL_SOCKET, exclusive, 1)
        else:
            listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            listener.bind((self.host, self.port))
        except OSError as err:
            listener.close()
            if err.errno in (errno.EADDRINUSE, getattr(errno, "WSAEADDRINUSE", errno.EADDRINUSE)):
                raise AddressInUse(
                    f"port {self.port} on {self.host} is in use (another world served here?): "
                    f"choose another with --port"
                ) from None
            raise
        listener.listen(16)
        self.listener = listener
        self.port = listener.getsockname()[1]
        return self.host, self.port

    # ------------------------------------------------------------------ filling
    def fill(self, seat_config: Callable[[int], dict]) -> list[Guest]:
        """Wait until every robot has a brick that greeted; those guests, robot by robot.

        seat_config(i): what robot i's seat message says (its name, the clock, the seed, the limits)."""
        assert self.listener is not None, "open() first"
        while True:
            ready_guests = [g for g in self.guests if g.greeting is not None]
            if len(ready_guests) == self.seats:
                return sorted(ready_guests, key=lambda g: g.seat)
            now = time.monotonic()
            waits = [g.deadline - now for g in self.guests if g.greeting is None]
            timeout = max(0.0, min(waits)) if waits else None
            socks = [self.listener, *(g.sock for g in self.guests if not g.finished)]
            readable, _, _ = select.select(socks, [], [], timeout)
            if self.listener in readable:
                self._accept()
            for guest in list(self.guests):
                if guest.sock in readable or guest.channel.data_waiting():
                    self._hear(guest, seat_config)
            now = time.monotonic()
            for guest in list(self.guests):
                if guest.greeting is None and now > guest.deadline and guest in self.guests:
                    what = "said who it is" if guest.seat is None else "had its brick ready"
                    self._drop(guest, f"it never {what} (waited {self._patience(guest):g} s)")

    def _patience(self, guest: Guest) -> float:
        return JOIN_TIMEOUT_S if guest.seat is None else START_TIMEOUT_S

    def _accept(self) -> None:
        try:
            sock, address = self.listener.accept()
        except OSError:
            return
        where = f"{address[0]}:{address[1]}"
        if sum(1 for g in self.guests if g.seat is None) >= MAX_WAITING:
            _refuse_now(sock, "too many connections are waiting to join this world; try again in a moment")
            self.log(f"a connection from {where} was turned away: too many waiting")
            return
        sock.setblocking(True)  # (a Python timeout would make every non-blocking read wait: see send_timeout)
        sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        send_timeout(sock, SEND_TIMEOUT_S)
        channel = Channel(sock)
        self.guests.append(Guest(sock, channel, where, time.monotonic() + JOIN_TIMEOUT_S))

    def _hear(self, guest: Guest, seat_config: Callable[[int], dict]) -> None:
        """Read what a guest sent, as far as its stage allows."""
        try:
            while guest in self.guests:
                message = guest.channel.pending()
                if guest.seat is None and guest.channel.buffered_bytes() > MAX_JOIN_BYTES:
                    raise ProtocolError(f"a join message longer than {MAX_JOIN_BYTES} bytes")
                if message is None:
                    return
                if guest.seat is None:
                    self._join(guest, message, seat_config)
                elif guest.greeting is None:
                    self._greet(guest, message)
                elif guest.channel.bytes_in <= MAX_EARLY_BYTES:
                    guest.early.append(message)
                else:
                    raise ProtocolError("it sent far too much before the run started")
        except ConnectionGone:
            if guest.seat is None:
                self._drop(guest, "it closed the connection without joining", quiet=True)
            elif guest.greeting is not None and _ended(guest):
                guest.finished = True  # its program ended before the run: the robot keeps it, and stays
            else:
                self._drop(
                    guest, f"it went away before the run started; robot {guest.seat + 1} is free again"
                )
        except ProtocolError as err:
            self._drop(guest, f"it does not speak ev3sim2d's protocol ({err})")

    def _join(self, guest: Guest, message: list, seat_config: Callable[[int], dict]) -> None:
        fields = check_join(message)
        guest.fields = fields
        if self.token is not None and not hmac.compare_digest(
            (fields["token"] or "").encode(), self.token.encode()
        ):
            why = "no join token" if not fields["token"] else "a wrong join token"
            return self._refuse(
                guest, why, f"{why}: ask for the token `ev3sim2d serve` printed and give it with --token"
            )
        taken = {g.seat: g for g in self.guests if g.seat is not None}
        wanted = fields["robot"]
        if wanted is not None and wanted > self.seats:
            return self._refuse(
                guest,
                f"it asked for robot {wanted}",
                f"this world has {self.seats} robot(s): choose --robot 1 to {self.seats}, or leave it out",
            )
        if wanted is not None and wanted - 1 in taken:
            holder = taken[wanted - 1]
            return self._refuse(
                guest,
                f"robot {wanted} is taken",
                f"robot {wanted} already has a program ({holder.fields['name']}'s {holder.fields['program']}); "
                "choose another with --robot, or leave it out to take a free one",
            )
        free = [i for i in range(self.seats) if i not in taken]
        if not free:
            return self._refuse(
                guest,
                "the world is full",
                f"the world is full: all {self.seats} robots have programs",
            )
        guest.seat = wanted - 1 if wanted is not None else free[0]
        guest.deadline = time.monotonic() + START_TIMEOUT_S
        guest.channel.send(["seat", {"protocol": PROTOCOL, **seat_config(guest.seat)}])
        self.log(f"robot {guest.seat + 1}: {guest.who} joined")

    def _greet(self, guest: Guest, message: list) -> None:
        if message[0] not in ("hello", "end") or len(message) != 2 or type(message[1]) is not dict:
            raise ProtocolError(f"its brick did not greet (it sent {str(message[0])[:40]!r})")
        guest.greeting = message
        left = self.seats - sum(1 for g in self.guests if g.greeting is not None)
        more = f"waiting for {left} more" if left else "every robot has a program"
        self.log(f"robot {guest.seat + 1}: its brick is ready; {more}")

    def _refuse(self, guest: Guest, short: str, why: str) -> None:
        try:
            guest.channel.send(["refused", why])
        except ProtocolError:
            pass
        self._drop(guest, f"refused: {short}", tell=False)

    def _drop(self, guest: Guest, why: str, quiet: bool = False, tell: bool = True) -> None:
        if tell and not quiet:
            try:
                send_timeout(guest.sock, 1.0)
                guest.channel.send(["refused", f"the world dropped this connection: {why}"])
            except (ProtocolError, OSError):
                pass
        _close(guest.sock)
        self.guests.remove(guest)
        if not quiet:
            self.log(f"{guest.who}: {why}")

    # ------------------------------------------------------------ during the run
    def refuse_during_run(self) -> None:
        """Turn away whoever comes while the run goes on (in a thread: the run never waits for it)."""
        if self.listener is None:
            return
        self._late = threading.Thread(target=self._turn_away, name="ev3sim2d-late-joins", daemon=True)
        self._late.start()

    def _turn_away(self) -> None:
        listener = self.listener
        while not self._closing:
            try:
                sock, _ = listener.accept()
            except OSError:
                return
            if self._closing:
                _close(sock)
                return
            _refuse_now(sock, f"the world is full: its {self.seats} robots are running; join the next run")

    def close(self) -> None:
        self._closing = True
        if self.listener is not None:
            try:
                self.listener.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
            _close(self.listener)
        for guest in self.guests:
            _close(guest.sock)


def is_loopback(host: str) -> bool:
    return host in LOOPBACK or host.startswith("127.")


def _ended(guest: Guest) -> bool:
    """Whether the brick said its program ended (its hello was the end, or an end came after it)."""
    return guest.greeting[0] == "end" or any(m[0] == "end" for m in guest.early)


def _refuse_now(sock: socket.socket, why: str) -> None:
    """Tell a connection why it is turned away, after reading what it said (closing a socket with
    unread data resets the connection, and the other side would never read why)."""
    try:
        sock.settimeout(1.0)  # (a socket no Channel reads)
        try:
            sock.recv(MAX_JOIN_BYTES)
        except OSError:
            pass
        sock.sendall(encode(["refused", why]))
        sock.shutdown(socket.SHUT_WR)
    except OSError:
        pass
    _close(sock)


def _close(sock: socket.socket) -> None:
    """Close, after reading what is waiting (so that the other side reads what it was last told)."""
    try:
        sock.setblocking(False)
        for _ in range(16):
            if not sock.recv(1 << 16):  # (non-blocking: BlockingIOError, an OSError, once nothing is left)
                break
    except OSError:
        pass
    try:
        sock.close()
    except OSError:
        pass
