"""MicroPython's `uheapq`: heappush, heappop, heapify (CPython's heapq)."""

from heapq import heapify, heappop, heappush  # noqa: F401
