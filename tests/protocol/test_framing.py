"""The brick protocol's framing: lines of JSON over a socket pair, or through shared memory."""

import os
import socket
import threading
import time

import pytest

from ev3sim2d.protocol import Channel, ProtocolError, SharedChannel, decode, encode, wait_for_any
from ev3sim2d.protocol.shared_memory import RING_BYTES, available, create_memory


def socket_pair():
    a, b = socket.socketpair()
    return Channel(a), Channel(b)


def shared_pair():
    a, b = socket.socketpair()
    fd = create_memory()
    pair = SharedChannel(a, os.dup(fd), simulator=True), SharedChannel(b, os.dup(fd), simulator=False)
    os.close(fd)
    return pair


KINDS = [socket_pair] + ([shared_pair] if available() else [])


@pytest.mark.parametrize("make", KINDS)
def test_messages_arrive_whole_and_in_order_whatever_they_hold(make):
    sim, brick = make()
    messages = [
        ["ops", [["k", 0, "tacho-motor", "motor0", "speed_sp"], ["w", 0, "300"], ["t", 10000]]],
        ["p", 5, "stdout", "a line\nwith a newline, ünïcödé and \u2028"],
        ["snap", 20000, ["40", [2, "No such file"]]],
    ]
    for m in messages:
        brick.send(m)
    assert [sim.receive(timeout_s=5) for _ in messages] == messages


@pytest.mark.parametrize("make", KINDS)
def test_a_message_larger_than_the_shared_ring_gets_through(make):
    sim, brick = make()
    big = ["c", 0, "display", ["ab" * (RING_BYTES // 2 + 12345)]]
    if not hasattr(os, "fork"):  # (Windows: a socket pair only) the brick side in a thread of this process
        sender = threading.Thread(target=lambda: (brick.send(big), brick.send(["end", {}])))
        sender.start()
        assert sim.receive(timeout_s=10) == big
        assert sim.receive(timeout_s=10) == ["end", {}]
        sender.join()
        return
    pid = os.fork()
    if pid == 0:  # the brick side, in a process of its own as in a run
        try:
            brick.send(big)
            brick.send(["end", {}])
        finally:
            os._exit(0)
    assert sim.receive(timeout_s=10) == big
    assert sim.receive(timeout_s=10) == ["end", {}]
    os.waitpid(pid, 0)


@pytest.mark.parametrize("make", KINDS)
def test_the_other_side_going_away_is_noticed(make):
    sim, brick = make()
    brick.send(["hello", {}])
    brick.close()
    assert sim.receive(timeout_s=5) == ["hello", {}]
    with pytest.raises(ProtocolError):
        sim.receive(timeout_s=5)


@pytest.mark.parametrize("make", KINDS)
def test_receive_times_out(make):
    sim, _brick = make()
    assert sim.receive(timeout_s=0.05) is None
    assert sim.pending() is None


@pytest.mark.parametrize("bad", [b"not json\n", b'{"a": 1}\n', b"[]\n", b"[1, 2]\n", b"[" * 100000 + b"\n"])
def test_anything_but_a_message_is_a_protocol_error(bad):
    a, b = socket.socketpair()
    sim = Channel(a)
    b.sendall(bad)
    with pytest.raises(ProtocolError):
        sim.receive(timeout_s=5)


def test_a_line_that_never_ends_is_cut_off():
    a, b = socket.socketpair()
    sim = Channel(a)
    b.setblocking(False)
    chunk = b"x" * 65536
    with pytest.raises(ProtocolError, match="longer than"):
        for _ in range(200):
            try:
                b.send(chunk)
            except BlockingIOError:
                pass
            sim.pending()


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_impossible_ring_positions_written_by_the_other_side_are_refused():
    sim, brick = shared_pair()
    words = memoryview(brick.memory).cast("Q")
    words[sim._in[0]] = 2**40  # the brick claims to have written a terabyte
    with pytest.raises(ProtocolError, match="impossible"):
        sim.pending()
    words.release()


def test_wait_for_any_says_which_channel_has_something():
    pairs = [socket_pair() for _ in range(3)]
    pairs[1][1].send(["ops", []])
    ready = wait_for_any([p[0] for p in pairs], 2.0)
    assert ready == [pairs[1][0]]
    assert wait_for_any([pairs[0][0]], 0.05) == []


def test_encode_and_decode_are_each_others_inverse():
    message = ["reply", [None, ["int", -1050, 1050]], ["40"]]
    assert decode(encode(message)[:-1]) == message


@pytest.mark.parametrize(
    "line, message",
    [(b' ["t", 1] ', ["t", 1]), (b'["snap",10000,["40"]]', ["snap", 10000, ["40"]]), (b'["x", NaN]', None)],
)
def test_decode_takes_json_arrays_with_spaces_around_them(line, message):
    if message is None:  # NaN is Python's JSON, not JSON: what encode can write must come back
        assert decode(line)[0] == "x"
    else:
        assert decode(line) == message


@pytest.mark.parametrize("bad", [b'["t", 1] x', b'["t", 1]]', b'["t", 1', b'"t"', b""])
def test_decode_refuses_what_follows_or_falls_short_of_one_array(bad):
    with pytest.raises(ProtocolError):
        decode(bad)


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_a_deferred_wake_up_is_sent_when_the_sender_is_about_to_wait():
    """When neither side may spin (runs share the cores), a sender wakes a sleeping reader only when it
    has nothing left to do itself (it is about to wait): on one core the woken process would take the
    core at once.  The message is in shared memory at once; the wake-up byte comes with flush_wakes."""
    from ev3sim2d.protocol.stream import flush_wakes

    sim, brick = shared_pair()
    sim.spin_s = 0.0
    assert sim.receive(timeout_s=0.01) is None  # no spinning: the simulator now defers its wake-ups
    brick.asleep(True)  # the brick sleeps on its socket
    sim.send(["snap", 10000, ["40"]])
    brick.sock.setblocking(False)
    with pytest.raises(BlockingIOError):
        brick.sock.recv(16)  # no wake-up yet
    assert brick.data_waiting()  # but the message is there for a reader that looks
    flush_wakes()
    assert brick.sock.recv(16) == b"w"
    brick.sock.setblocking(True)
    brick.asleep(False)
    assert brick.receive(timeout_s=1) == ["snap", 10000, ["40"]]


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_a_sender_that_may_spin_wakes_a_sleeping_reader_at_once():
    sim, brick = shared_pair()
    brick.asleep(True)
    sim.send(["snap", 10000, []])
    assert brick.sock.recv(16) == b"w"


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_a_brick_defers_its_wake_ups_only_when_the_simulator_says_it_may():
    """With several bricks, one that computes on without waiting would hold up the world for the others:
    the simulator lets a brick defer its wake-ups only when it is the only one."""
    sim, brick = shared_pair()
    sim.spin_s = 0.0
    sim.sock.setblocking(False)
    for may_defer, woken in ((False, True), (True, False)):
        sim.peer_may_defer = may_defer
        assert sim.receive(timeout_s=0.01) is None  # the simulator publishes what the brick may do
        assert brick.receive(timeout_s=0.01) is None  # and the brick reads it
        sim.asleep(True)
        brick.send(["ops", [["t", 10000]]])
        try:
            got = sim.sock.recv(16) == b"w"
        except BlockingIOError:
            got = False
        assert got is woken
        sim.asleep(False)
        assert sim.receive(timeout_s=1) == ["ops", [["t", 10000]]]


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_what_a_side_wrote_before_it_died_without_waking_the_other_is_still_read():
    """A brick that defers its wake-ups and is killed right after writing (a program that kills its
    own process) leaves no wake-up byte, only the socket's end: the simulator, asleep, must still read
    the brick's last messages before it says the brick is gone."""
    sim, brick = shared_pair()
    brick._defer = True  # as when the simulator lets it defer
    sim.spin_s = 0.0  # the simulator sleeps on its socket at once
    pid = os.fork()
    if pid == 0:
        try:
            time.sleep(0.2)  # the simulator is asleep by now
            brick.send(["ops", [["t", 1000000]]])  # no wake-up: deferred
            brick.sock.close()  # its end of the socket goes at once, as when the process dies
        finally:
            os._exit(0)
    brick.close()
    assert sim.receive(timeout_s=5) == ["ops", [["t", 1000000]]]
    os.waitpid(pid, 0)
    with pytest.raises(ProtocolError):
        sim.receive(timeout_s=5)


@pytest.mark.skipif(not available(), reason="shared memory channel: x86-64 Linux only")
def test_pending_takes_every_shape_of_what_the_ring_holds():
    """One whole message is decoded where it lies in shared memory; several at once, a part of one, one
    that wraps round the ring's end and one that is not a message go through the buffer: all come out as
    they were sent, one at a time, and what is not the protocol is refused."""
    sim, brick = shared_pair()
    one, two = ["ops", [["w", 3, "250"], ["t", 10000]]], ["p", 5, "stdout", "a line"]
    brick.send(one)
    assert sim.pending() == one
    assert sim.pending() is None
    brick.send(one)
    brick.send(two)
    assert [sim.pending(), sim.pending(), sim.pending()] == [one, two, None]
    brick.send_bytes(b'["ops", [["t", ')  # half a message: nothing yet
    assert sim.pending() is None
    brick.send_bytes(b"20000]]]\n")
    assert sim.pending() == ["ops", [["t", 20000]]]
    filler = ["f", "x" * 100_000]
    size = len(encode(filler))
    while brick._written % RING_BYTES + size <= RING_BYTES:
        brick.send(filler)
        assert sim.pending() == filler
    brick.send(filler)  # across the ring's end
    assert sim.pending() == filler
    assert sim.pending() is None
    brick.send_bytes(b'{"not": "a message"}\n')
    with pytest.raises(ProtocolError):
        sim.pending()
