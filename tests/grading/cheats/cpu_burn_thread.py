# ruff: noqa
"""Burn CPU in threads: a threading.Thread that spins, and a real OS thread (through the unpatched
`_thread.start_new_thread` the simulator keeps) that spins, while the main program sleeps to the time limit.

Contained: the threads are stopped at the lesson's limits, with the run; the other submissions keep
their scores and the class run ends in its usual time plus the limits; this program scores at most
what standing still scores.
"""

import sys
import threading
import time

MARKER = "EV3CHEAT-cpu-burn-thread"


def burn():
    while True:
        try:
            while True:
                pass
        except BaseException:
            pass


threading.Thread(target=burn, daemon=True).start()
real_start = getattr(sys.modules.get("ev3sim2d.simulator.program"), "_real_start_new_thread", None)
if real_start is not None:
    real_start(burn, ())
time.sleep(60)
