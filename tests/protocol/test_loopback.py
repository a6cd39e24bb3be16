"""A brick over loopback TCP (protocol/loopback.py): only the brick that knows the token gets in.

Any program on the computer can connect to a port on 127.0.0.1; the simulator must take none of
them for its brick: not one that connects first and says nothing, nor one with a wrong or an
overlong token, nor one that speaks something else.  It waits on for the right one.
"""

from __future__ import annotations

import socket
import threading
import time

from ev3sim2d.protocol import encode
from ev3sim2d.protocol.loopback import HOST, LoopbackListener, connect


def test_the_brick_with_the_token_gets_in_and_talks():
    listener = LoopbackListener()
    try:
        brick = []
        threading.Thread(target=lambda: brick.append(connect(listener.port, listener.token))).start()
        simulator = listener.accept(10.0)
        assert simulator is not None
        simulator.send(["welcome", {"robot": "robot"}])
        deadline = time.monotonic() + 5
        while not brick and time.monotonic() < deadline:
            time.sleep(0.01)
        assert brick[0].receive(timeout_s=5) == ["welcome", {"robot": "robot"}]
        brick[0].send(["hello", {}])
        assert simulator.receive(timeout_s=5) == ["hello", {}]
    finally:
        listener.close()


def test_others_on_the_computer_are_turned_away_and_the_brick_still_gets_in():
    listener = LoopbackListener()
    try:
        silent = socket.create_connection((HOST, listener.port))  # connects first, says nothing
        wrong = socket.create_connection((HOST, listener.port))
        wrong.sendall(encode(["brick", {"token": "0" * 32}]))
        long = socket.create_connection((HOST, listener.port))
        long.sendall(encode(["brick", {"token": listener.token + "x" * 500}]))
        nonsense = socket.create_connection((HOST, listener.port))
        nonsense.sendall(b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n")
        brick = []
        threading.Timer(0.2, lambda: brick.append(connect(listener.port, listener.token))).start()
        started = time.monotonic()
        simulator = listener.accept(30.0)
        assert simulator is not None
        simulator.send(["welcome", {}])
        assert brick[0].receive(timeout_s=5) == ["welcome", {}]
        assert time.monotonic() - started < 12  # a silent one holds the door at most HELLO_TIMEOUT_S
        for intruder in (wrong, long, nonsense):
            intruder.settimeout(5)
            assert intruder.recv(100) == b"", "an intruder's connection was kept"
        silent.close()
    finally:
        listener.close()


def test_no_brick_in_time_or_a_brick_that_ended_gives_none():
    listener = LoopbackListener()
    try:
        assert listener.accept(0.3) is None
        assert listener.accept(30.0, still_starting=lambda: False) is None
    finally:
        listener.close()


def test_the_token_is_new_each_time_and_the_port_only_on_loopback():
    first, second = LoopbackListener(), LoopbackListener()
    try:
        assert first.token != second.token and len(first.token) == 32
        assert first.sock.getsockname()[0] == "127.0.0.1"
    finally:
        first.close()
        second.close()
