# ruff: noqa
"""Kill everything: `os.kill(-1, SIGKILL)`, every process the program may signal, the grader included.

Contained: the signal reaches no process outside the program's own: the grader finishes the class
with exit status 0 and complete reports, the other submissions keep their scores.  This program is
killed itself or stands still: it scores at most what standing still scores.
"""

import os
import signal

MARKER = "EV3CHEAT-kill-everything"

try:
    os.kill(-1, signal.SIGKILL)
except OSError as err:
    print("cannot:", err)
