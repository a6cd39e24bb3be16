"""MicroPython's `uselect` (unix port): poll and select, with CPython's select."""

from select import POLLERR, POLLHUP, POLLIN, POLLOUT, poll, select  # noqa: F401
