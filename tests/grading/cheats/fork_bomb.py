# ruff: noqa
"""Fork bomb: processes that fork for ever, each in a session of its own (out of the run's process group,
which the grader kills), waiting for a free process slot when there is none: the grader then cannot
start its next runs.  The first children become small fresh Pythons (`python -S -c ...`, the marker in
their command line), which fork fast.

The test grades this only inside a pids cgroup with a limit, so it never fills a real machine.

Contained: the program's processes are limited and end with its run: the class run ends with exit
status 0 and complete reports, the other submissions keep their scores, no process of the bomb
survives the grader; this program scores at most what standing still scores.
"""

import os
import select
import sys

MARKER = "EV3CHEAT-fork-bomb"
BOMB = """
import os, select
while True:
    try:
        if os.fork() == 0:
            os.setsid()
    except OSError:
        select.select([], [], [], 0.5)
"""

while True:
    try:
        if os.fork() == 0:
            try:
                os.setsid()
                os.execv(sys.executable, [sys.executable, "-S", "-c", BOMB, MARKER])
            finally:
                os.abort()
    except OSError:
        select.select([], [], [], 0.5)  # no process slot free: wait for one, in real time
