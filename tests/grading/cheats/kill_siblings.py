# ruff: noqa
"""Kill the classmates' runs: while it runs, SIGKILL every process it can see that is not itself or the grader
(the other runs under --jobs 2 are forked from the grader: same command line), each one and its process group.

It keeps at it for a few seconds of real time in each of its runs, so that the runs graded beside
it die and score 0.

Contained: the program sees no other process (its own PID namespace, another user): the other
submissions keep their scores; the program stands still and scores what standing still scores.
"""

import os
import select
import signal
import time

MARKER = "EV3CHEAT-kill-siblings"
REAL_SECONDS = 6.0

me, grader = os.getpid(), os.getppid()
killed = set()
started = os.times().elapsed
while os.times().elapsed - started < REAL_SECONDS:
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) in (me, grader, 1):
            continue
        pid = int(entry)
        try:
            os.killpg(os.getpgid(pid), signal.SIGKILL) if os.getpgid(pid) != os.getpgid(me) else None
            os.kill(pid, signal.SIGKILL)
            killed.add(pid)
        except OSError:
            pass
    select.select([], [], [], 0.02)  # real time
    time.sleep(0.001)  # and a little simulated time, so the run is not stopped as stuck
print("killed", len(killed), "processes")
