# ruff: noqa
"""Flood the console: write without end to file descriptors 1 and 2 (not through print, which the simulator
records line by line), to fill the disk or the grader's logs.

Contained: stopped at the lesson's output limit; the reports stay small; the other submissions keep
their scores; this program scores at most what standing still scores.
"""

import os

MARKER = "EV3CHEAT-endless-output"

block = (MARKER + " " + "x" * 1000 + "\n").encode() * 64
while True:
    try:
        os.write(1, block)
        os.write(2, block)
    except OSError:
        pass
