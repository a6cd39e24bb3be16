"""Who may talk to a page server on 127.0.0.1 (`edit`, `live`), and how much of it at once.

Everything that can reach 127.0.0.1 is not the student: a web page they visit, another account on the
same computer.  So each server start draws a random key (the page token); the address it prints and opens
carries it in the URL fragment (`http://127.0.0.1:PORT/#token=...`), which a browser never sends to a
server nor in a Referer.  The page keeps it in sessionStorage (one origin, one tab) and sends it as the
header X-Ev3sim2d-Token on every request - reads, the event stream and the LCD image included, all with
fetch, so the key is never in a URL the browser logs or a server sees.  The page's own files (HTML, JS,
CSS, no data) are served without it.  Requests from another site's page (Sec-Fetch-Site, Origin,
Referer) are refused whatever they ask for, before the key is looked at.  Where the system says which
account holds the other end of a connection (Linux: /proc/net/tcp), another account is turned away.

The server keeps at most MAX_CONNECTIONS connections; a request must arrive within REQUEST_TIMEOUT_S.
Past the cap, the oldest connection that is waiting for a request is closed to make room (idle sockets
cannot lock the page out); when every connection is busy, the newcomer gets 503 at once.
"""

from __future__ import annotations

import hmac
import os
import secrets
import socket
import sys
import threading
import time
from http.server import ThreadingHTTPServer

TOKEN_HEADER = "X-Ev3sim2d-Token"
MAX_CONNECTIONS = 48
REQUEST_TIMEOUT_S = 15.0
MAX_JSON_DEPTH = 32
PROC_NET_TCP = "/proc/net/tcp"

# The security headers every answer carries (the page is never framed, never tells where it was).
PAGE_POLICY = "default-src 'self'; img-src 'self' data: blob:; frame-ancestors 'none'; form-action 'self'"
SECURITY_HEADERS = (
    ("Cache-Control", "no-store"),
    ("X-Content-Type-Options", "nosniff"),
    ("Content-Security-Policy", PAGE_POLICY),
    ("X-Frame-Options", "DENY"),
    ("Referrer-Policy", "no-referrer"),
    ("Cross-Origin-Resource-Policy", "same-origin"),
)
_BUSY_BODY = b'{"error": "the server is busy (too many connections); try again in a moment"}'
BUSY_ANSWER = (
    b"HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json; charset=utf-8\r\n"
    + b"".join(f"{name}: {value}\r\n".encode() for name, value in SECURITY_HEADERS)
    + f"Content-Length: {len(_BUSY_BODY)}\r\nConnection: close\r\nRetry-After: 1\r\n\r\n".encode()
    + _BUSY_BODY
)


def new_token() -> str:
    """A fresh page token: 32 random bytes, URL-safe."""
    return secrets.token_urlsafe(32)


def token_matches(sent: str | None, token: str) -> bool:
    """Whether a request's token is the server's, compared in constant time."""
    return sent is not None and hmac.compare_digest(sent.encode("utf-8", "replace"), token.encode("utf-8"))


def json_depth_ok(value: object, limit: int = MAX_JSON_DEPTH) -> bool:
    """Whether parsed JSON nests no deeper than `limit` lists/objects (checked without recursion)."""
    stack = [(value, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (dict, list)):
            if depth > limit:
                return False
            children = item.values() if isinstance(item, dict) else item
            stack.extend((child, depth + 1) for child in children)
    return True


def _hex_address(host: str, port: int) -> str:
    """An IPv4 address and port as /proc/net/tcp writes them (the address in the machine's byte order)."""
    packed = socket.inet_aton(host)
    return f"{int.from_bytes(packed, sys.byteorder):08X}:{port:04X}"


def peer_uid(client: tuple[str, int], server: tuple[str, int], table: str = PROC_NET_TCP) -> int | None:
    """The account that owns the client's end of a connection on this computer, or None where the system
    does not tell (no /proc/net/tcp, or the connection is not listed)."""
    try:
        with open(table, encoding="ascii", errors="replace") as handle:
            lines = handle.read().splitlines()[1:]
    except OSError:
        return None
    try:
        local, remote = _hex_address(*client), _hex_address(*server)
    except (OSError, ValueError):
        return None
    for line in lines:
        fields = line.split()
        if len(fields) > 7 and fields[1] == local and fields[2] == remote:
            try:
                return int(fields[7])
            except ValueError:
                return None
    return None


def _own_uids() -> set[int] | None:
    """The accounts allowed to connect (ours, and the administrator's), or None where there are no uids."""
    if not hasattr(os, "geteuid"):
        return None
    return {os.geteuid(), os.getuid(), 0}


class PageServer(ThreadingHTTPServer):
    """A ThreadingHTTPServer on 127.0.0.1 with a page token, a connection cap and per-request timeouts."""

    daemon_threads = True
    request_queue_size = 64

    def __init__(self, port: int, handler_class) -> None:
        self.token = new_token()
        self._connections: dict[int, list] = {}  # id -> [socket, waiting since (or None when busy)]
        self._connections_lock = threading.Lock()
        self._next_id = 0
        self._own_uids = _own_uids()
        self._serving = threading.local()  # each connection's thread: its id in _connections
        super().__init__(("127.0.0.1", port), handler_class)

    @property
    def url(self) -> str:
        """The page's address, with the token in its fragment (what the student opens)."""
        return f"http://127.0.0.1:{self.server_address[1]}/#token={self.token}"

    @property
    def bare_url(self) -> str:
        return f"http://127.0.0.1:{self.server_address[1]}/"

    @property
    def open_connections(self) -> int:
        with self._connections_lock:
            return len(self._connections)

    # -- who may connect -----------------------------------------------------------------------
    def verify_request(self, request, client_address) -> bool:
        """Turn away another account where the system tells who holds the other end (Linux)."""
        if self._own_uids is None:
            return True
        uid = peer_uid(client_address, self.server_address)
        return uid is None or uid in self._own_uids

    # -- how many at once ----------------------------------------------------------------------
    def process_request(self, request, client_address) -> None:
        with self._connections_lock:
            if len(self._connections) >= MAX_CONNECTIONS and not self._evict_oldest_waiting():
                self._answer_busy(request)
                return
            self._next_id += 1
            connection_id = self._next_id
            self._connections[connection_id] = [request, time.monotonic()]
        thread = threading.Thread(
            target=self._serve_connection, args=(request, client_address, connection_id), daemon=True
        )
        thread.start()

    def _serve_connection(self, request, client_address, connection_id: int) -> None:
        self._serving.connection_id = connection_id
        try:
            self.process_request_thread(request, client_address)
        finally:
            with self._connections_lock:
                self._connections.pop(connection_id, None)

    def _evict_oldest_waiting(self) -> bool:
        """Close the connection that has waited longest for a request (lock held); False if none waits."""
        waiting = [(since, key) for key, (_sock, since) in self._connections.items() if since is not None]
        if not waiting:
            return False
        _since, key = min(waiting)
        sock = self._connections.pop(key)[0]
        try:
            sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        return True

    def _answer_busy(self, request) -> None:
        try:
            request.settimeout(0.5)
            request.sendall(BUSY_ANSWER)
        except OSError:
            pass
        self.shutdown_request(request)

    def mark(self, waiting: bool) -> None:
        """The calling connection waits for a request (it may be closed for room) or is busy serving one."""
        connection_id = getattr(self._serving, "connection_id", None)
        with self._connections_lock:
            entry = self._connections.get(connection_id)
            if entry is not None:
                entry[1] = time.monotonic() if waiting else None
