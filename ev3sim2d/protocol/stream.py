"""Framing: messages as lines of JSON over a stream socket (a socket pair, a Unix socket or TCP).

Waiting for a message first spins for a short while on non-blocking reads (a
brick and its simulator on one machine answer each other within microseconds,
far sooner than a process that went to sleep is woken), then blocks; on a
machine whose cores are all busy it blocks at once.
"""

from __future__ import annotations

import os
import select
import socket
import struct
import time

from .messages import MAX_MESSAGE_BYTES, ConnectionGone, ProtocolError, decode, encode

_perf_counter = time.perf_counter  # the real clock, whatever a program does to `time` later
_DONTWAIT = getattr(socket, "MSG_DONTWAIT", None)  # None: not on this system (Windows): select first
_CORES = os.cpu_count() or 1
# looks: the last three, 1 for crowded; ours: this run's processes that spin as they wait for each other (the
# simulator and its bricks), and whether they have cores of their own (spinning_processes)
_load = {"checked": -1.0, "idle": True, "looks": 0, "ours": 2, "own_cores": False}
LOAD_CHECK_S = 0.05
_deferred_wakes: list = []  # channels whose reader may sleep and has not been woken yet


def defer_wake(channel) -> None:
    """Wake channel's reader only when this process is about to wait (flush_wakes), not now."""
    _deferred_wakes.append(channel)


def flush_wakes() -> None:
    """Before this process blocks: wake the readers it deferred.  On a shared core a woken process
    takes the core at once, so a process that wakes its peer only when it has nothing left to do
    lets both work through every tick they can before the core changes hands."""
    while _deferred_wakes:
        _deferred_wakes.pop().wake_now()


def can_spin() -> bool:
    """Whether a connection here can wait by spinning (reading without blocking: not on Windows)."""
    return _DONTWAIT is not None


def spinning_processes(count: int, own_cores: bool) -> None:
    """How many processes of this run spin while they wait for each other (the simulator and its bricks: 2
    unless told), and whether they were given cores of their own (simulator/cores.py).  More of them than
    cores may spin only then: left to the scheduler, four sumo bricks on two cores ran at 15-20x real time
    spinning, 25x blocking, and 55-60x on cores of their own (benchmarks/robots.py)."""
    _load["ours"], _load["own_cores"] = count, own_cores
    _load.update(checked=-1.0, looks=0, idle=True)


def cores_idle() -> bool:
    """Whether this machine has a core to spare for spinning: looked at every LOAD_CHECK_S from the number of
    processes running then, and idle unless two of the last three looks found more than there are cores.  A
    moment's crowd (a brick starting, a kernel thread) is not a busy machine: decided on one look, a run
    that began at such a moment would wake its peer by a system call at every message until the next look,
    four times slower, and a short run never looks again.  A run on cores of its own (simulator/cores.py)
    counts its own spinning processes and one thread more, and stops spinning only when all three looks
    found more: with two of three, a thread of its own at two looks made a quarter of such runs block on
    every message for a while, 150x real time instead of 210x (two line followers)."""
    ours = _load["ours"]
    if ours > _CORES and not _load["own_cores"]:
        return False
    now = _perf_counter()
    if now - _load["checked"] > LOAD_CHECK_S:
        _load["checked"] = now
        if _load["own_cores"]:  # (a thread of ours beside them, the memory watch's, may run at a look too)
            looks = _load["looks"] = (_load["looks"] << 1 | _crowded(ours + 1)) & 0b111
            _load["idle"] = looks != 0b111
        else:
            looks = _load["looks"] = (_load["looks"] << 1 | _crowded(max(_CORES, ours))) & 0b111
            _load["idle"] = looks not in (0b011, 0b101, 0b110, 0b111)
    return _load["idle"]


def machine_busy() -> bool:
    """One look now: more processes running than cores (before a run starts its bricks: others')."""
    return _crowded(_CORES)


def _crowded(room: int) -> bool:
    """Whether more than `room` processes are running now (ours are running too while they spin)."""
    try:
        with open("/proc/loadavg", "rb") as f:
            return int(f.read().split()[3].split(b"/")[0]) > room
    except (OSError, ValueError, IndexError):
        try:
            return os.getloadavg()[0] >= room - 0.5
        except (OSError, AttributeError):  # (no load average on Windows)
            return False


class Channel:
    """One end of a connection: send messages, receive them in order."""

    def __init__(self, sock: socket.socket, spin_s: float = 0.002) -> None:
        self.sock = sock
        self.spin_s = spin_s if _DONTWAIT is not None else 0.0
        self._buffer = bytearray()
        self._start = 0
        self.closed = False
        self.bytes_in = 0  # bytes read from the socket so far
        self.peer_may_defer = False  # (shared memory only: see SharedChannel)

    def fileno(self) -> int:
        return self.sock.fileno()

    def set_spin(self, spin_s: float) -> None:
        """How long this side spins before it sleeps when it waits (0: it never spins), from now on."""
        self.spin_s = spin_s if _DONTWAIT is not None else 0.0

    # ------------------------------------------------------------------ sending
    def send(self, message: list) -> None:
        self.send_bytes(encode(message))

    def send_bytes(self, data: bytes) -> None:
        try:
            self.sock.sendall(data)
        except OSError as err:
            self.closed = True
            raise ConnectionGone(f"the connection is gone ({err})") from None

    # ---------------------------------------------------------------- receiving
    def pending(self) -> list | None:
        """The next message if one has arrived already, else None (never waits)."""
        if self._buffer:  # (an empty buffer holds no message: read first)
            message = self._take()
            if message is not None:
                return message
        while self._fill_now():
            message = self._take()
            if message is not None:
                return message
        return None

    def receive(self, timeout_s: float | None = None) -> list | None:
        """The next message, waiting up to timeout_s (None: for ever); None when the time is up."""
        message = self._take()
        if message is not None:
            return message
        if self.spin_s and cores_idle():
            end = _perf_counter() + self.spin_s
            while True:
                if self._fill_now():
                    message = self._take()
                    if message is not None:
                        return message
                elif _perf_counter() > end:
                    break
        deadline = None if timeout_s is None else _perf_counter() + timeout_s
        while True:
            left = None if deadline is None else deadline - _perf_counter()
            if left is not None and left <= 0:
                return None
            flush_wakes()
            if left is not None:
                ready, _, _ = select.select([self.sock], [], [], left)
                if not ready:
                    return None
            self._fill(0)
            message = self._take()
            if message is not None:
                return message

    def _fill(self, flags: int) -> bool:
        """Read what the socket has (waiting for something unless flags say not to); False if nothing."""
        data = self._recv(1 << 16, flags)
        if data is None:
            return False
        self._buffer += data
        self.bytes_in += len(data)
        return True

    def _fill_now(self) -> bool:
        """Read what the socket has now, never waiting; False if nothing."""
        if _DONTWAIT is not None:
            return self._fill(_DONTWAIT)
        ready, _, _ = select.select([self.sock], [], [], 0)
        return bool(ready) and self._fill(0)

    def _recv(self, size: int, flags: int) -> bytes | None:
        """Bytes from the socket, None if none are there yet; ConnectionGone once the other side is."""
        try:
            data = self.sock.recv(size, flags)
        except (BlockingIOError, InterruptedError):
            return None
        except OSError as err:
            self.closed = True
            raise ConnectionGone(f"the connection is gone ({err})") from None
        if not data:
            self.closed = True
            raise ConnectionGone("the other side closed the connection")
        return data

    def _take(self) -> list | None:
        buffer = self._buffer
        end = buffer.find(b"\n", self._start)
        if end < 0:
            if len(buffer) - self._start > MAX_MESSAGE_BYTES:
                raise ProtocolError(f"a message longer than {MAX_MESSAGE_BYTES} bytes")
            if self._start:
                del buffer[: self._start]
                self._start = 0
            return None
        line = bytes(buffer[self._start : end])
        self._start = end + 1
        if self._start == len(buffer):
            buffer.clear()
            self._start = 0
        return decode(line)

    # ------------------------------------------------------ waiting on several
    def data_waiting(self) -> bool:
        """Whether a whole message is here already (without reading the socket)."""
        return self._buffer.find(b"\n", self._start) >= 0

    def buffered_bytes(self) -> int:
        """How many bytes have arrived that are not yet a whole message."""
        return len(self._buffer) - self._start

    def asleep(self, flag: bool) -> None:
        """A channel whose data does not come through the socket is told its reader blocks on it."""

    def take_wakeups(self) -> None:
        """After select: nothing to do here (the data itself is on the socket)."""

    def wake_now(self) -> None:
        """A deferred wake-up (none here: a socket's reader wakes when the data arrives)."""

    def close(self) -> None:
        self.closed = True
        try:
            self.sock.close()
        except OSError:
            pass


def send_timeout(sock: socket.socket, seconds: float) -> None:
    """Sending fails (and so drops the connection) when the other side takes no data for this long; the
    kernel's timeout, which leaves reads alone.  Windows takes it as a DWORD of milliseconds, POSIX
    systems as a struct timeval, which refuse the shorter form: so the DWORD is tried first."""
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDTIMEO, max(1, int(seconds * 1000)))
        return
    except OSError:
        pass
    whole = int(seconds)
    sock.setsockopt(
        socket.SOL_SOCKET, socket.SO_SNDTIMEO, struct.pack("ll", whole, int((seconds - whole) * 1e6))
    )


def wait_for_any(channels: list[Channel], timeout_s: float) -> list[Channel]:
    """Block until one of the channels may have something (or timeout_s); those that may."""
    waiting = [c for c in channels if c.data_waiting()]
    if waiting:
        return waiting
    for channel in channels:
        channel.asleep(True)
    try:
        waiting = [c for c in channels if c.data_waiting()]
        if waiting:
            return waiting
        flush_wakes()
        ready, _, _ = select.select(channels, [], [], timeout_s)
        for channel in ready:
            channel.take_wakeups()
        return [c for c in channels if c in ready or c.data_waiting()]
    finally:
        for channel in channels:
            channel.asleep(False)
