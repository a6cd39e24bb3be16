"""Bluetooth between the bricks of one session: Pybricks' mailbox connections, in virtual time.

A Pybricks 2.0 program talks to another EV3 through pybricks.messaging (pybricks-micropython v2.0.0,
bricks/ev3dev/modules/pybricks/messaging.py): a BluetoothMailboxServer listens on RFCOMM channel 1, a
BluetoothMailboxClient connects to it by the other brick's name or address, and both send mailbox
messages (a name and some bytes) that the other end keeps, the latest value per name.  Here each
brick's connection objects are *endpoints* (numbered per brick), a connection is a *link* between a
client endpoint and a server endpoint, and messages travel on links with a Bluetooth latency.

Bricks and names: every other brick of the session is paired with every brick.  A brick answers to
its robot's name (`robot1`, `robot2`, ... as in the trace), to its address (00:16:53:00:00:01 for
robot 1: LEGO's prefix), and, as every EV3 is named `ev3dev` until renamed, to `ev3dev`, which
resolves (as bluetooth_c.resolve does: the first paired device whose alias matches) to the first
other robot.  A brick is never paired with itself.

Determinism: what a brick does at its clock t reaches another brick at t + latency_us or later, and
latency_us is at least a tick.  A brick's request at its clock c is applied when the world is at the
tick at or before c, when every brick's ops before that tick have been applied (session.py), so
everything due by c is known then, and nothing later is looked at: each answer depends only on the
programs, never on which process was faster.  Messages due by the world's time are moved into their
mailbox as soon as they are known, so a mailbox nobody reads keeps one value per name.

Bounds (a brick is a student's program): a frame of at most FRAME_BYTES (the firmware's 16-bit size
field), mailbox names of at most NAME_BYTES (its 8-bit name size), MAILBOXES names a connection keeps
(messages to more are lost), ENDPOINTS connection objects a brick makes, a sender that waits while
its link has SEND_BUFFER_BYTES in flight, as a socket's send does.
"""

from __future__ import annotations

import errno
from collections import deque
from dataclasses import dataclass, field

from ..protocol import ProtocolError

LATENCY_US = 20_000  # a mailbox message's trip from one EV3 to the other (Bluetooth, RFCOMM)
BYTE_US = 10  # sending a byte: about 100 kB/s through RFCOMM
CONNECT_US = 1_000_000  # a client's connect (paging the other brick, then RFCOMM), refused or not
SEND_BUFFER_BYTES = 16_384  # bytes a socket holds in flight before send waits
FRAME_BYTES = 65_535  # the 16-bit size of a mailbox frame (messaging.py: MailboxHandlerMixIn.send_to_mailbox)
FRAME_HEADER = 7  # message count, command type, command, name size, data size
NAME_BYTES = 254  # a mailbox name, whose size with its final NUL is one byte
MAILBOXES = 256  # names a connection object keeps (the firmware sets no bound)
ENDPOINTS = 32  # connection objects (servers and clients) a brick makes in a run
BRICK_NAME_CHARS = 1_000  # a brick name or address asked for (longer ones match no paired device)
LEGO_PREFIX = "00:16:53"
EV3_NAME = "ev3dev"


def address(index: int) -> str:
    """The Bluetooth address of robot index (0-based)."""
    number = index + 1
    return f"{LEGO_PREFIX}:{number >> 16 & 255:02X}:{number >> 8 & 255:02X}:{number & 255:02X}"


@dataclass(eq=False)
class _Endpoint:
    """A BluetoothMailboxServer or BluetoothMailboxClient of one brick: its mailboxes and connections."""

    brick: int
    number: int
    store: dict = field(default_factory=dict)  # mailbox name -> [data, updates]
    links: list = field(default_factory=list)  # connections in use, in the order they were made
    connecting: dict = field(default_factory=dict)  # a client's connect under way: server brick -> link


@dataclass(eq=False)
class _Link:
    """One RFCOMM connection from a client endpoint to a brick's server."""

    client: _Endpoint
    server_brick: int
    connected_us: int  # when the client's connect completes (or is refused)
    server: _Endpoint | None = None  # the server endpoint it reached, once decided
    refused: bool | None = None
    accepted_us: int | None = None
    closed: dict = field(default_factory=dict)  # brick -> when it closed its end
    queues: dict = field(
        default_factory=dict
    )  # receiving brick -> deque of [due_us, sender, seq, name, data]
    free_us: dict = field(default_factory=dict)  # sending brick -> when its last byte has left

    def peer(self, brick: int) -> int:
        return self.server_brick if brick == self.client.brick else self.client.brick

    def key(self) -> tuple:
        return (self.connected_us, self.client.brick, self.client.number)


class Mailboxes:
    """The Bluetooth of one session's bricks: the feature `mailbox` of the protocol (docs/protocol.md)."""

    def __init__(self, ports: list, tick_us: int) -> None:
        self.ports = ports
        self.tick_us = tick_us
        self.latency_us = max(LATENCY_US, tick_us)
        self.endpoints: list[list[_Endpoint]] = [[] for _ in ports]
        self.listening: list[list[tuple[int, _Endpoint | None]]] = [[] for _ in ports]
        self.links: list[_Link] = []
        self.seq = 0
        for port in ports:
            port.mailboxes = self

    # ------------------------------------------------------------ who is who
    def resolve(self, asker: int, name) -> int | None:
        """The brick a name or address means to this brick (bluetooth_c.resolve over its paired devices)."""
        if type(name) is not str or len(name) > BRICK_NAME_CHARS:
            return None
        for index, port in enumerate(self.ports):
            if index == asker:
                continue
            if name == port.robot.name or name == EV3_NAME or name.upper() == address(index):
                return index
        return None

    def _ended_us(self, brick: int) -> int | None:
        port = self.ports[brick]
        if not port.finished:
            return None
        end = port.end
        return end["t_us"] if end is not None and type(end.get("t_us")) is int else port.time_us

    def _listener(self, brick: int, at_us: int) -> _Endpoint | None:
        """The server endpoint the brick listened with at at_us, if any."""
        ended = self._ended_us(brick)
        if ended is not None and ended <= at_us:
            return None
        listening = None
        for since, endpoint in self.listening[brick]:
            if since > at_us:
                break
            listening = endpoint
        return listening

    def _closed(self, link: _Link, brick: int, now_us: int) -> bool:
        """Has this brick's link been closed at the other end, as this brick sees it at now_us?"""
        peer = link.peer(brick)
        closed = link.closed.get(peer)
        ended = self._ended_us(peer)
        if ended is not None:
            closed = ended if closed is None else min(closed, ended)
        return closed is not None and closed + self.latency_us <= now_us

    def _decide(self, link: _Link) -> None:
        """Whether the client's connect reached a listening server (as that server was a trip earlier)."""
        if link.refused is None:
            server = self._listener(link.server_brick, link.connected_us - self.latency_us)
            link.refused = server is None
            link.server = server

    # ------------------------------------------------------------ the feature
    def call(self, port, args: list):
        """One request of a brick's pybricks.messaging, at its clock (port.time_us)."""
        if not args or type(args[0]) is not str:
            raise ProtocolError("a mailbox call is [request, ...]")
        request, rest = args[0], args[1:]
        handler = _REQUESTS.get(request)
        if handler is None:
            raise ProtocolError(f"no mailbox request {request[:50]!r}")
        return handler(self, port.index, port.time_us, *rest)

    def _endpoint(self, brick: int, number) -> _Endpoint:
        endpoints = self.endpoints[brick]
        if type(number) is not int or not 0 <= number < len(endpoints):
            raise ProtocolError("a mailbox call names a connection object the brick did not make")
        return endpoints[number]

    def _new_endpoint(self, brick: int) -> _Endpoint | None:
        endpoints = self.endpoints[brick]
        if len(endpoints) >= ENDPOINTS:
            return None
        endpoint = _Endpoint(brick, len(endpoints))
        endpoints.append(endpoint)
        return endpoint

    def server(self, brick: int, now_us: int) -> list:
        """A BluetoothMailboxServer binds channel 1 and listens (one at a time: EADDRINUSE)."""
        if self._listener(brick, now_us) is not None:
            return ["OSError", errno.EADDRINUSE]
        endpoint = self._new_endpoint(brick)
        if endpoint is None:
            return ["OSError", errno.ENOMEM]
        self.listening[brick].append((now_us, endpoint))
        return ["ok", endpoint.number]

    def client(self, brick: int, now_us: int) -> list:
        endpoint = self._new_endpoint(brick)
        return ["OSError", errno.ENOMEM] if endpoint is None else ["ok", endpoint.number]

    def server_close(self, brick: int, now_us: int, number) -> list:
        """The server stops listening; the connections it accepted go on (RFCOMMServer.server_close)."""
        endpoint = self._endpoint(brick, number)
        if self._listener(brick, now_us) is endpoint:
            self.listening[brick].append((now_us, None))
        return ["ok"]

    def accept(self, brick: int, now_us: int, number):
        """A connection that reached this server by now, accepted; None while there is none (asked again
        each tick); ["closed"] for a server that no longer listens (its accept fails)."""
        endpoint = self._endpoint(brick, number)
        if self._listener(brick, now_us) is not endpoint:
            return ["closed"]
        waiting = []
        for link in self.links:
            if link.server_brick == brick and link.accepted_us is None and link.connected_us <= now_us:
                self._decide(link)
                if link.server is endpoint:
                    waiting.append(link)
        if not waiting:
            return None
        link = min(waiting, key=_Link.key)
        link.accepted_us = now_us
        endpoint.links.append(link)
        return ["ok", address(link.client.brick)]

    def connect(self, brick: int, now_us: int, number, name) -> list:
        """A client's connect: resolved now, decided CONNECT_US later ("connected")."""
        endpoint = self._endpoint(brick, number)
        if type(name) is not str:
            raise ProtocolError("a brick's name is text")
        other = self.resolve(brick, name)
        if other is None:
            return ["ValueError", "no paired devices matching"]
        if other in endpoint.connecting or any(link.peer(brick) == other for link in endpoint.links):
            return ["ValueError", "connection with this address already exists"]
        link = _Link(endpoint, other, now_us + CONNECT_US)
        self.links.append(link)
        endpoint.connecting[other] = link
        return ["pending", CONNECT_US, address(other)]

    def connected(self, brick: int, now_us: int, number, name):
        """The end of a connect: None until it is decided, then ["ok"] or ECONNREFUSED."""
        endpoint = self._endpoint(brick, number)
        other = self.resolve(brick, name)
        link = endpoint.connecting.get(other)
        if link is None:
            raise ProtocolError("no connect under way to that brick")
        if now_us < link.connected_us:
            return None
        del endpoint.connecting[other]
        self._decide(link)
        if link.refused:
            return ["OSError", errno.ECONNREFUSED]
        endpoint.links.append(link)
        return ["ok"]

    def close(self, brick: int, now_us: int, number) -> list:
        """A client's close: its connections end (the other end sees it a trip later)."""
        endpoint = self._endpoint(brick, number)
        for link in [*endpoint.links, *endpoint.connecting.values()]:
            link.closed[brick] = now_us
            link.queues.pop(brick, None)
        endpoint.links = []
        endpoint.connecting = {}
        return ["ok"]

    def send(self, brick: int, now_us: int, number, destination, name, data_hex) -> list:
        """A mailbox message to every connection of the endpoint (destination None) or to one brick;
        answered with how long the sender waits for room in its socket."""
        endpoint = self._endpoint(brick, number)
        if type(name) is not str or type(data_hex) is not str:
            raise ProtocolError("a mailbox message is a name and its data as hex")
        name_bytes = len(name.encode("utf-8", "surrogatepass"))
        if name_bytes > NAME_BYTES or FRAME_HEADER + name_bytes + 1 + len(data_hex) // 2 > FRAME_BYTES:
            raise ProtocolError(f"a mailbox message is {FRAME_BYTES} bytes at most, its name {NAME_BYTES}")
        data = bytes.fromhex(data_hex)
        if destination is None:
            links = list(endpoint.links)
        else:
            other = self.resolve(brick, destination)
            if other is None:
                return ["ValueError", "no paired devices matching"]
            links = [link for link in endpoint.links if link.peer(brick) == other]
            if not links:
                return ["KeyError", address(other)]
        frame = FRAME_HEADER + name_bytes + 1 + len(data)
        wait_us = 0
        for link in links:
            if self._closed(link, brick, now_us):
                return ["OSError", errno.ENOTCONN]
            peer = link.peer(brick)
            free = max(now_us, link.free_us.get(brick, 0)) + frame * BYTE_US
            link.free_us[brick] = free
            self.seq += 1
            queue = link.queues.setdefault(peer, deque())
            queue.append([free + self.latency_us, brick, self.seq, name, data])
            receiver = link.server if peer == link.server_brick else link.client
            self._deliver(receiver, self.ports[brick].declared)  # (the world's time: see the docstring)
            if len(queue) > 1 and receiver is link.server and link.accepted_us is None:
                _keep_latest(queue)  # (not accepted yet: only the last value of each name will count)
            wait_us = max(wait_us, free - SEND_BUFFER_BYTES * BYTE_US - now_us)
        return ["ok", wait_us]

    def read(self, brick: int, now_us: int, number, name, seen=None):
        """A mailbox's [updates, data as hex or None]; with `seen` (the updates a wait started from), None
        until there are others (asked again each tick)."""
        endpoint = self._endpoint(brick, number)
        if type(name) is not str:
            raise ProtocolError("a mailbox name is text")
        self._deliver(endpoint, now_us)
        updates, data = endpoint.store.get(name, (0, None))
        if seen is not None and updates == seen:
            return None
        return [updates, None if data is None else data.hex()]

    def _deliver(self, endpoint: _Endpoint, until_us: int) -> None:
        """Move what is due by until_us into the endpoint's mailboxes, in order of arrival."""
        brick = endpoint.brick
        due = []
        for link in endpoint.links:
            queue = link.queues.get(brick)
            start = link.accepted_us if endpoint is link.server else None
            while queue and max(queue[0][0], start or 0) <= until_us:
                item = queue.popleft()
                due.append((max(item[0], start or 0), *item[1:]))
        due.sort(key=lambda item: item[:3])
        store = endpoint.store
        for _, _, _, name, data in due:
            kept = store.get(name)
            if kept is not None:
                kept[0] += 1
                kept[1] = data
            elif len(store) < MAILBOXES:
                store[name] = [1, data]


def _keep_latest(queue: deque) -> None:
    """Of the messages queued on a connection, only the last of each name."""
    latest: dict = {}
    for item in queue:
        latest[item[3]] = item
    if len(latest) < len(queue):
        kept = sorted(latest.values(), key=lambda item: item[2])
        queue.clear()
        queue.extend(kept)


_REQUESTS = {
    "server": Mailboxes.server,
    "client": Mailboxes.client,
    "server_close": Mailboxes.server_close,
    "accept": Mailboxes.accept,
    "connect": Mailboxes.connect,
    "connected": Mailboxes.connected,
    "close": Mailboxes.close,
    "send": Mailboxes.send,
    "read": Mailboxes.read,
}
