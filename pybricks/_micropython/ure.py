"""MicroPython's `ure`: compile, match, search, sub (CPython's re, which knows more syntax)."""

from re import DEBUG, compile, match, search, sub  # noqa: F401
