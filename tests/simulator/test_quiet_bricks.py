"""Quiet waits (protocol 2's "u", brick/link.py poll): a brick that waits for a motor is not told of each
tick, and the run is the same, fingerprint and printed lines, as with every brick told of every tick
(EV3SIM2D_EVERY_TICK=1): alone and with four robots in the sumo ring."""

from __future__ import annotations

import pytest

from ev3sim2d.simulator.brick_port import BrickPort
from ev3sim2d.simulator.bricks import EVERY_TICK
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.session import Session
from ev3sim2d.world.maze_file import find_maze, load_maze

WAKES = BrickPort.wakes

SLEEPS = """
from time import sleep
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
tank = MoveTank(OUTPUT_B, OUTPUT_C)
for i in range(4):
    tank.on(30, -30)
    sleep(0.37)
    tank.on(40, 40)
    sleep(0.21)
    print(i)
"""

WAITS = """
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor
tank = MoveTank(OUTPUT_B, OUTPUT_C)
floor = ColorSensor(INPUT_3)
for i in range(3):
    tank.on_for_seconds(30, 30, 0.7)
    print(floor.reflected_light_intensity)
    tank.on_for_degrees(30, -30, 180)
    tank.on_for_seconds(-20, -20, 0.33, block=True)
"""

POLLS = """
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
from ev3dev2.sensor import INPUT_3, INPUT_4
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor
tank = MoveTank(OUTPUT_B, OUTPUT_C)
floor = ColorSensor(INPUT_3)
eyes = UltrasonicSensor(INPUT_4)
tank.on(35, 35)
n = 0
while floor.reflected_light_intensity > 30 and eyes.distance_centimeters > 12 and n < 300:
    n += 1
print(n, floor.reflected_light_intensity, eyes.distance_centimeters)
tank.off()
"""

THREADS = """
import threading
from time import sleep
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, LargeMotor
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor
left, right = LargeMotor(OUTPUT_B), LargeMotor(OUTPUT_C)
floor = ColorSensor(INPUT_3)

def watch():
    for i in range(12):
        sleep(0.137)
        print("watch", floor.reflected_light_intensity, right.position)

threading.Thread(target=watch).start()
for i in range(3):
    left.on_for_seconds(25, 0.61)
    right.on_for_degrees(40, 300)
    print("moved", left.position, right.position)
"""

PYBRICKS = """
from pybricks.ev3devices import Motor
from pybricks.parameters import Port
left, right = Motor(Port.B), Motor(Port.C)
for i in range(3):
    left.run_time(300, 700, wait=False)
    right.run_time(-300, 900)
    left.run_angle(200, 250)
    print(left.angle(), right.angle())
"""

STOPPED = """
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_seconds(10, -10, 1.0)
print("turned")
tank.on_for_seconds(20, 20, 60)
"""


def _run(tmp_path, monkeypatch, source: str, robots: int, every_tick: bool, limit_s: float = 6.0) -> tuple:
    program = tmp_path / "program.py"
    program.write_text(source)
    monkeypatch.setenv(EVERY_TICK, "1" if every_tick else "0")
    woken = []

    def counted(port, label_us):
        woke = WAKES(port, label_us)
        woken.append(woke)
        return woke

    monkeypatch.setattr(BrickPort, "wakes", counted)
    result = run_programs([program] * robots, load_maze(find_maze("sumo-4")), time_limit_s=limit_s)
    assert result.error is None, result.error
    output = [(line.robot, line.t_s, line.text) for line in result.trace.output]
    return result.trace.fingerprint(), output, (result.status, result.reason), woken


@pytest.mark.parametrize("robots", [1, 4])
@pytest.mark.parametrize("name", ["SLEEPS", "WAITS", "POLLS", "THREADS", "PYBRICKS"])
def test_quiet_waits_run_as_every_tick(tmp_path, monkeypatch, name: str, robots: int) -> None:
    source = globals()[name]
    every = _run(tmp_path, monkeypatch, source, robots, every_tick=True)
    quiet = _run(tmp_path, monkeypatch, source, robots, every_tick=False)
    assert quiet[:3] == every[:3]
    assert every[3] == []  # (no brick waited quietly)
    if name in (
        "WAITS",
        "THREADS",
        "PYBRICKS",
    ):  # the motors' waits were quiet: ticks looked at by the simulator, few of them woke
        assert quiet[3].count(False) > 5 * quiet[3].count(True) > 0
    assert every[1], every[2]  # (the programs printed)


@pytest.mark.parametrize("robots", [1, 4])
def test_the_time_limit_ends_a_quiet_wait_where_it_ended_a_wait_tick_by_tick(tmp_path, monkeypatch, robots):
    """The simulator stops a brick that waits quietly at the time limit: the same trace, and the same
    place in the program (the run's reason names the line of the wait)."""
    every = _run(tmp_path, monkeypatch, STOPPED, robots, every_tick=True, limit_s=2.345)
    quiet = _run(tmp_path, monkeypatch, STOPPED, robots, every_tick=False, limit_s=2.345)
    assert quiet[:3] == every[:3]
    assert every[2][0] == "time_limit" and "line 6" in every[2][1], every[2]
    assert quiet[3].count(False) > 50


@pytest.mark.parametrize("robots", [1, 4])
def test_a_run_in_steps_with_quiet_waits_is_the_run_in_one_go(tmp_path, monkeypatch, robots):
    """A live run's pace (Session.advance, 37 ms at a time: stops that fall inside quiet waits) gives the
    same run as one that goes through, every brick told of every tick."""
    every = _run(tmp_path, monkeypatch, WAITS, robots, every_tick=True)

    def in_steps(session: Session) -> None:
        until = 0
        while not session.advance(until):
            until += 37_000
        session.finish()

    monkeypatch.setattr(Session, "run", in_steps)
    quiet = _run(tmp_path, monkeypatch, WAITS, robots, every_tick=False)
    assert quiet[:3] == every[:3]
    assert quiet[3].count(True) > 0
