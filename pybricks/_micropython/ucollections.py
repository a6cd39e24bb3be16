"""MicroPython's `ucollections`: namedtuple, OrderedDict, deque (CPython's collections)."""

from collections import OrderedDict, deque, namedtuple  # noqa: F401
