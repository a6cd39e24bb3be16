# ruff: noqa
"""Spin for ever: `while True: pass`, catching whatever is raised in it to stop it.

Contained: stopped at the lesson's limits (as stuck, or at the CPU or wall-clock limit); the other
submissions keep their scores and the class run ends in its usual time plus the limits; this
program scores at most what standing still scores.
"""

MARKER = "EV3CHEAT-busy-loop"

while True:
    try:
        while True:
            pass
    except BaseException:
        pass
