"""MicroPython's `ujson`: dump, dumps, load, loads (CPython's json)."""

from json import dump, dumps, load, loads  # noqa: F401
