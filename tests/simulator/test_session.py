"""The simulator's side of the lockstep (session.py, brick_port.py), driven by hand-made bricks.

A brick is a student's program: these bricks send what a hostile or broken one could, and the
simulator must apply the protocol's rules, drop that brick with a reason, and go on."""

import socket

import pytest

from ev3sim2d.protocol import Channel
from ev3sim2d.simulator.brick_port import BrickPort
from ev3sim2d.simulator.session import Session
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.maze_file import parse_maze

TICK = 10_000


def world_with(n_robots=1):
    starts = "\n".join(f"  - {{x_cm: {60 + 60 * i}, y_cm: 120, heading_deg: 0}}" for i in range(n_robots))
    rows = "\n".join("  " + r for r in ["#" * 20] + ["#" + "." * 18 + "#"] * 18 + ["#" * 20])
    return parse_maze(f"title: t\ncell_cm: 12\ngrid: |\n{rows}\nstart:\n{starts}\n", "<test>")


def session_with(messages_per_brick, limit_us=2_000_000, hang_after_s=0.5, close=True):
    """A session whose bricks have already sent these messages (raw bytes or lists)."""
    world = world_with(len(messages_per_brick))
    sim = Simulation(world, [(f"r{i}", world.robot, world.starts[i]) for i in range(len(messages_per_brick))])
    ports, brick_ends = [], []
    for i, messages in enumerate(messages_per_brick):
        ours, theirs = socket.socketpair()
        brick = Channel(theirs)
        for m in messages:
            brick.send_bytes(m) if isinstance(m, bytes) else brick.send(m)
        if close:
            brick.close()
        brick_ends.append(brick)
        ports.append(BrickPort(i, sim.robots[i], Channel(ours), sim.trace, []))
    return Session(sim, ports, limit_us, hang_after_s), ports, sim, brick_ends


def drive(ticks, speed="300"):
    ops = [["k", 0, "tacho-motor", "motor1", "speed_sp"], ["k", 1, "tacho-motor", "motor1", "command"]]
    ops += [["W", 0, speed], ["W", 1, "run-forever"]]
    ops += [["t", TICK * (i + 1)] for i in range(ticks)]
    return ["ops", ops]


def test_a_brick_that_ends_properly_leaves_its_world_at_its_end_time():
    session, ports, sim, _ = session_with([[drive(50), ["end", {"t_us": 505_000, "status": "finished"}]]])
    session.run()
    assert ports[0].end["status"] == "finished"
    assert ports[0].gone is None
    assert session.world_us == 505_000
    assert len(sim.trace.times) == 50
    assert sim.robots[0].x > sim.robots[0].start.x_cm  # motor1 (outB, the left wheel) drove it ahead


@pytest.mark.parametrize(
    "bad, why",
    [
        (b"this is not json\n", "protocol"),
        (["ops", [["w", 7, "300"]]], "undefined key"),
        (["ops", [["k", 5, "tacho-motor", "motor1", "speed_sp"]]], "in order"),
        (["ops", [["t", 50_000], ["t", 20_000]]], "back in time"),
        (["ops", [["p", 0, "stdout", 42]]], "printed line"),
        (["ops", [["frobnicate"]]], "unknown op"),
        (["ops", "everything"], "unexpected message"),
        (["snap", 0, []], "unexpected message"),
        (["ops", [["w", 0, 300]]], "text"),
        (["end", {"t_us": -5, "status": "finished"}], "back in time"),
    ],
)
def test_a_brick_that_breaks_the_protocol_is_dropped_with_the_reason(bad, why):
    session, ports, _sim, _ = session_with([[drive(3), bad]])
    session.run()
    assert ports[0].gone is not None and ports[0].gone.startswith("protocol"), ports[0].gone
    assert why in ports[0].gone


def test_one_brick_dropped_does_not_stop_the_others():
    good = [drive(100), ["end", {"t_us": 1_000_000, "status": "finished"}]]
    bad = [drive(10), b"garbage\n"]
    session, ports, sim, _ = session_with([good, bad])
    session.run()
    assert ports[1].gone.startswith("protocol")
    assert ports[0].end["status"] == "finished"
    assert session.world_us == 1_000_000
    assert len(sim.trace.times) == 100


def test_a_silent_brick_is_stopped_as_hung():
    session, ports, _sim, ends = session_with([[drive(5)]], hang_after_s=0.3, close=False)
    session.run()
    assert ports[0].gone == "hung"
    assert session.world_us == 5 * TICK
    ends[0].close()


def test_the_world_never_passes_the_time_limit_whatever_a_brick_says():
    session, ports, sim, _ = session_with([[drive(500)]], limit_us=1_000_000)
    session.run()
    assert session.world_us == 1_000_000
    assert len(sim.trace.times) == 100
    assert ports[0].end["status"] == "time_limit"


def test_a_brick_gone_without_a_word_is_noticed():
    session, ports, _sim, _ = session_with([[drive(5)]])
    session.run()
    assert ports[0].gone.startswith("gone")


def test_output_is_cut_to_size():
    long_line = "x" * 10_000
    session, ports, sim, _ = session_with(
        [[["ops", [["p", 0, "stdout", long_line]] * 3], ["end", {"t_us": 0, "status": "finished"}]]]
    )
    session.run()
    assert all(len(line.text) < 2100 for line in sim.trace.output)
    assert len(sim.trace.output) == 3
