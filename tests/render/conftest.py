"""Traces to draw: short runs of small programs in small inline worlds, made once per test session."""

import textwrap

import pytest

from ev3sim2d.simulator.run import run_programs
from tests.inline_world import arena

DRIVER = """
    from ev3dev2.led import Leds
    from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
    from ev3dev2.sound import Sound

    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    Leds().set_color("LEFT", "RED")
    print("off we go")
    Sound().beep("-f 880 -l 300")
    tank.on_for_seconds(50, 50, 2.5)
    Sound().speak("done")
    print("done")
"""


def run_inline(tmp_path_factory, source: str, world=None, time_limit_s: float = 10.0):
    path = tmp_path_factory.mktemp("prog") / "prog.py"
    path.write_text(textwrap.dedent(source))
    world = world or arena(width=12, height=8, cell_cm=12, start="x_cm: 30\n  y_cm: 48\n  heading_deg: 0")
    return run_programs([path], world, None, time_limit_s, 0, 5.0, None).trace


@pytest.fixture(scope="session")
def driving_trace(tmp_path_factory):
    """A robot that beeps, drives 2.5 s to the right, speaks and stops: about 3.7 s of run."""
    return run_inline(tmp_path_factory, DRIVER)
