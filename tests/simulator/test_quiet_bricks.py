"""Quiet waits (protocol 2's "u", brick/link.py poll): a brick that waits for a motor is not told of each
tick, and the run is the same, fingerprint and printed lines, as with every brick told of every tick
(EV3SIM2D_EVERY_TICK=1): alone and with four robots in the sumo ring."""

from __future__ import annotations

import pytest

from ev3sim2d.simulator.brick_port import BrickPort
from ev3sim2d.simulator.bricks import EVERY_TICK
from ev3sim2d.simulator.run import run_programs
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


def _run(tmp_path, monkeypatch, source: str, robots: int, every_tick: bool) -> tuple:
    program = tmp_path / "program.py"
    program.write_text(source)
    monkeypatch.setenv(EVERY_TICK, "1" if every_tick else "0")
    woken = []

    def counted(port, label_us):
        woke = WAKES(port, label_us)
        woken.append(woke)
        return woke

    monkeypatch.setattr(BrickPort, "wakes", counted)
    result = run_programs([program] * robots, load_maze(find_maze("sumo-4")), time_limit_s=6.0)
    assert result.error is None, result.error
    output = [(line.robot, line.t_s, line.text) for line in result.trace.output]
    return result.trace.fingerprint(), output, result.status, woken


@pytest.mark.parametrize("robots", [1, 4])
@pytest.mark.parametrize("name", ["SLEEPS", "WAITS", "POLLS"])
def test_quiet_waits_run_as_every_tick(tmp_path, monkeypatch, name: str, robots: int) -> None:
    source = globals()[name]
    every = _run(tmp_path, monkeypatch, source, robots, every_tick=True)
    quiet = _run(tmp_path, monkeypatch, source, robots, every_tick=False)
    assert quiet[:3] == every[:3]
    assert every[3] == []  # (no brick waited quietly)
    if name == "WAITS":  # the motors' waits were quiet: ticks looked at by the simulator, few of them woke
        assert quiet[3].count(False) > 5 * quiet[3].count(True) > 0
    assert every[1], every[2]  # (the programs printed)
