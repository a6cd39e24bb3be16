# ruff: noqa
"""Eat memory: grab memory in big blocks until the system has none, catching MemoryError to go on.

Contained: stopped at the lesson's memory limit; the other submissions keep their scores; this
program scores at most what standing still scores.
"""

MARKER = "EV3CHEAT-memory-hog"

hoard = []
for _ in range(100_000):
    try:
        hoard.append(bytearray(64 << 20))
    except MemoryError:
        hoard = hoard[: len(hoard) // 2]
