"""MicroPython's `uhashlib`: sha256 and sha1 (CPython's hashlib)."""

from hashlib import sha1, sha256  # noqa: F401
