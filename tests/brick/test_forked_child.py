"""A program that forks: only the brick's own process is in lockstep with the world.

On an EV3 a forked child is a process of its own; here it shares the brick's connection, so it must
never write to it (a stray line from it once corrupted the stream, at random: the run then ended as
"hung" or with a protocol error).  The child's printed lines go to the console, its use of a
device or of the clock ends it, and the run is the parent's, every time.
"""

from __future__ import annotations

import os

import pytest

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork on this system")

FORK_AND_EXEC = """
import os, sys, time
if os.fork() == 0:
    os.execv(sys.executable, [sys.executable, "-c", "import time; time.sleep(2)"])
time.sleep(0.5)
print("parent done")
"""

FORK_AND_GO_ON = """
import os, time
from ev3dev2.motor import LargeMotor, OUTPUT_B
if os.fork() == 0:
    print("the child prints")
    LargeMotor(OUTPUT_B).on_for_seconds(50, 1)
    print("never here")
time.sleep(0.5)
print("parent done")
"""


@pytest.mark.parametrize("source", [FORK_AND_EXEC, FORK_AND_GO_ON], ids=["exec", "go on"])
def test_a_forked_child_never_speaks_for_the_brick(run, source):
    for _ in range(6):  # (it went wrong one run in five)
        result = run(source)
        assert result.status == "finished", result.reason
        assert [line.text for line in result.trace.output] == ["parent done"]
        assert result.sim_time_s == pytest.approx(0.501)  # (the printed line costs 1 ms)
