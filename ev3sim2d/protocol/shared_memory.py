"""Framing for a brick on the same computer: the same lines of JSON, through shared memory.

Two byte rings in one shared memory file (a memfd the simulator makes and the
brick inherits): one for each direction.  Each ring has a producer position
(bytes written so far), a consumer position (bytes read so far) and the
consumer's "asleep" flag, each on a cache line of its own.  Sending copies the
bytes in and moves the producer position; receiving copies what is there out.
A waiting side spins on the positions for a short while, then says it sleeps
and waits on the socket pair, which carries nothing but wake-up bytes (sent
only to a sleeper) and tells when the other process is gone.  A wake-up that
crosses the flag is caught by the sleeper's short select timeout.  Spinning pays
only while a core is free: the simulator looks at the machine's load and says
in shared memory whether the brick (which cannot see it) may spin.  When nobody
spins, a sender wakes a sleeper only when it is about to wait itself (see
stream.flush_wakes), and a brick does so only if the simulator says it may.

So a message costs two memory copies and no system call while both sides are
busy, instead of a send and a receive.  Positions written by the other side are
checked before use (the other side may be a student's program); each side
keeps its own positions itself and only publishes them.  Only on x86-64, whose
memory order makes the two stores (bytes, then position) visible in order.
"""

from __future__ import annotations

import mmap
import os
import platform
import select
import socket
import time

from .messages import MAX_MESSAGE_BYTES, ConnectionGone, ProtocolError, decode
from .stream import Channel, cores_idle, defer_wake, flush_wakes

RING_BYTES = 1 << 20
if RING_BYTES >= MAX_MESSAGE_BYTES:  # (SharedChannel.pending takes a whole message from the ring unchecked)
    raise ImportError("the shared memory ring must be smaller than the longest message")
HEADER_BYTES = 256  # producer position, consumer position, asleep flag: 64 bytes apart
SIZE = 2 * (HEADER_BYTES + RING_BYTES)
SLEEP_CHECK_S = 0.002  # a sleeper looks again this often, whatever the wake-ups do
SEND_TIMEOUT_S = 10.0  # a full ring the other side never empties ends the connection
_perf_counter = time.perf_counter  # the real clocks, bound before a brick makes `time` virtual
_sleep = time.sleep
_yield = getattr(os, "sched_yield", lambda: None)


def available() -> bool:
    """Whether this computer can use the shared memory channel."""
    return hasattr(os, "memfd_create") and platform.machine().lower() in ("x86_64", "amd64")


def create_memory() -> int:
    """A new shared memory file for one brick's two rings; its fd is passed to the brick."""
    fd = os.memfd_create("ev3sim2d-brick", 0)
    os.ftruncate(fd, SIZE)
    return fd


class SharedChannel(Channel):
    """One end of a brick connection through shared memory; `simulator` says which end."""

    def __init__(self, sock: socket.socket, memory_fd: int, simulator: bool, spin_s: float = 0.002) -> None:
        super().__init__(sock, spin_s)
        self.memory = mmap.mmap(memory_fd, SIZE)
        os.close(memory_fd)
        sock.setblocking(True)
        words = memoryview(self.memory).cast("Q")
        ring_words = (HEADER_BYTES + RING_BYTES) // 8
        to_brick, to_simulator = 0, ring_words
        out_ring, in_ring = (to_brick, to_simulator) if simulator else (to_simulator, to_brick)
        self._words = words
        # word indexes: producer position, consumer position, consumer asleep
        self._out = (out_ring, out_ring + 8, out_ring + 16)
        self._in = (in_ring, in_ring + 8, in_ring + 16)
        self._spin_word = to_brick + 24  # 1 while the simulator finds a core free for spinning
        self._defer_word = to_brick + 28  # 1 when the brick may defer its wake-ups (see peer_may_defer)
        # (simulator's end: peer_may_defer says whether its brick may wake it only when the brick
        # waits; only with one brick: with several, one that computes on would hold up the others)
        self._simulator = simulator
        self._out_data = out_ring * 8 + HEADER_BYTES
        self._in_data = in_ring * 8 + HEADER_BYTES
        self._written = 0  # our producer position (ours: never read back from shared memory)
        self._defer = False  # wake the reader only when this process waits (when neither side spins)
        self._wake_deferred = False
        self._read = 0  # our consumer position

    # ------------------------------------------------------------------ sending
    def send_bytes(self, data: bytes) -> None:
        if self.closed:
            raise ConnectionGone("the connection is gone")
        words, memory = self._words, self.memory
        produced_at, consumed_at, asleep_at = self._out
        size, written = len(data), self._written
        start = written % RING_BYTES
        if start + size <= RING_BYTES and 0 <= written - words[consumed_at] <= RING_BYTES - size:
            # the usual case, a message with room for it before the ring's end: one copy
            at = self._out_data + start
            memory[at : at + size] = data
            self._written = written + size
            words[produced_at] = written + size
        else:
            self._send_wrapping(data)
        if not self._defer:
            self._wake(asleep_at)
        elif not self._wake_deferred:
            self._wake_deferred = True
            defer_wake(self)

    def _send_wrapping(self, data: bytes) -> None:
        """send_bytes for a message that wraps round the ring's end or must wait for room."""
        words, memory = self._words, self.memory
        produced_at, consumed_at, asleep_at = self._out
        view = memoryview(data)
        deadline = None
        while view:
            consumed = words[consumed_at]
            free = RING_BYTES - (self._written - consumed)
            if free <= 0 or free > RING_BYTES:
                if free > RING_BYTES or free < 0:
                    free = 0  # a consumer position we never produced: treat the ring as full
                deadline = deadline or _perf_counter() + SEND_TIMEOUT_S
                if _perf_counter() > deadline:
                    self.closed = True
                    raise ProtocolError("the other side does not read")
                self._wake(asleep_at)
                _sleep(0.0001)
                continue
            start = self._written % RING_BYTES
            n = min(len(view), free, RING_BYTES - start)
            memory[self._out_data + start : self._out_data + start + n] = view[:n]
            self._written += n
            words[produced_at] = self._written
            view = view[n:]

    def wake_now(self) -> None:
        """The deferred wake-up (see stream.flush_wakes): the reader may read what was sent."""
        self._wake_deferred = False
        if not self.closed:
            try:
                self._wake(self._out[2])
            except ConnectionGone:
                pass  # the reader is gone: its next read says so

    def _wake(self, asleep_at: int) -> None:
        if self._words[asleep_at]:
            try:
                self.sock.send(b"w", socket.MSG_DONTWAIT)
            except BlockingIOError:
                pass  # the sleeper has wake-ups enough
            except OSError as err:
                self.closed = True
                raise ConnectionGone(f"the connection is gone ({err})") from None

    # ---------------------------------------------------------------- receiving
    def pending(self) -> list | None:
        """Channel.pending, with its usual case short (the simulator takes a message from each brick a
        tick): nothing buffered, and what the ring holds, before its end, is one whole message: decoded
        from shared memory where it lies, without passing through the buffer.  Anything else (a part of a
        message, several, one that wraps round the ring, a position that cannot be) goes the long way.
        (No message that fits in the ring is over MAX_MESSAGE_BYTES, the longest the long way takes.)"""
        if not self._buffer:
            words = self._words
            produced = words[self._in[0]]
            count = produced - self._read
            if count == 0:
                return None
            start = self._read % RING_BYTES
            if 0 < count and start + count <= RING_BYTES:
                at, memory = self._in_data + start, self.memory
                end = at + count - 1  # where its newline is, if it is one whole message
                if memory[end] == 10 and memory.find(b"\n", at, end) < 0:
                    data = memory[at:end]
                    self._read = produced
                    words[self._in[1]] = produced
                    return decode(data)
        return super().pending()

    def _fill(self, flags: int) -> bool:
        words = self._words
        produced = words[self._in[0]]
        count = produced - self._read
        if count == 0:
            if flags == 0:
                self._sleep_until_data()
                return self._fill(socket.MSG_DONTWAIT)
            return False
        if count < 0 or count > RING_BYTES:
            self.closed = True
            raise ProtocolError("the other side's ring position is impossible")
        start = self._read % RING_BYTES
        first = min(count, RING_BYTES - start)
        base = self._in_data
        self._buffer += self.memory[base + start : base + start + first]
        if first < count:
            self._buffer += self.memory[base : base + count - first]
        self._read = produced
        words[self._in[1]] = produced
        return True

    def set_spin(self, spin_s: float) -> None:
        """Channel.set_spin; the simulator's end tells its brick at once (the brick spins only when told)."""
        super().set_spin(spin_s)
        if self._simulator:
            self._may_spin()

    def _may_spin(self) -> bool:
        """The simulator looks at the machine's load (and tells the brick, which cannot see it)."""
        words = self._words
        if self._simulator:
            idle = self.spin_s > 0 and cores_idle()
            words[self._spin_word] = 1 if idle else 0
            words[self._defer_word] = 1 if self.peer_may_defer and not idle else 0
            self._defer = not idle
        else:
            idle = bool(words[self._spin_word])
            self._defer = not idle and bool(words[self._defer_word])
        return idle

    def data_waiting(self) -> bool:
        return self._words[self._in[0]] != self._read or bool(self._buffer)

    def asleep(self, flag: bool) -> None:
        """Say (in shared memory) whether this side waits on the socket for a wake-up."""
        self._words[self._in[2]] = 1 if flag else 0

    def take_wakeups(self) -> None:
        """Read the wake-up bytes off the socket; ConnectionGone if the other side is gone, once what it
        wrote before it went has been read (a side that defers its wake-ups may end without one)."""
        try:
            self._recv(4096, socket.MSG_DONTWAIT)
        except ConnectionGone:
            if self._words[self._in[0]] == self._read:
                raise
            self.closed = False  # not yet: its last messages are still in the ring

    def _sleep_until_data(self, timeout_s: float | None = None) -> bool:
        """Block (not spin) until bytes arrive or timeout_s; False when the time is up."""
        deadline = None if timeout_s is None else _perf_counter() + timeout_s
        in_produced = self._in[0]
        words = self._words
        self.asleep(True)
        flush_wakes()
        try:
            while words[in_produced] == self._read:
                wait = SLEEP_CHECK_S
                if deadline is not None:
                    wait = min(wait, deadline - _perf_counter())
                    if wait <= 0:
                        return False
                ready, _, _ = select.select([self.sock], [], [], wait)
                if ready:
                    self.take_wakeups()
            return True
        finally:
            self.asleep(False)

    def receive(self, timeout_s: float | None = None) -> list | None:
        message = self.pending()
        if message is not None:
            return message
        end = _perf_counter() + (self.spin_s if self._may_spin() else 0.0)
        while True:
            message = self.pending()
            if message is not None:
                return message
            if _perf_counter() > end:
                break
            _yield()  # a busy machine: let the other side (perhaps on this core) run
        deadline = None if timeout_s is None else _perf_counter() + timeout_s
        while True:
            left = None if deadline is None else deadline - _perf_counter()
            if left is not None and left <= 0:
                return None
            if not self._sleep_until_data(left):
                return None
            self._fill(socket.MSG_DONTWAIT)
            message = self._take()
            if message is not None:
                return message

    def close(self) -> None:
        super().close()
        if not self._simulator:
            return  # in a brick the sandbox closed the mapping's own descriptor: leave the mapping be
        try:
            self._words.release()
            self.memory.close()
        except (BufferError, ValueError):
            pass
