"""MicroPython's `uio`: open, StringIO, BytesIO, FileIO, TextIOWrapper (CPython's io)."""

import io as _io
from io import BytesIO, FileIO, StringIO, TextIOWrapper  # noqa: F401

open = _io.open
