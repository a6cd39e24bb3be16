"""MicroPython's `uzlib`: decompress(data, wbits=0) (CPython's zlib)."""

import zlib as _zlib


def decompress(data, wbits=0, bufsize=0):
    """The data decompressed: a zlib stream, or with a negative wbits a raw deflate stream."""
    return _zlib.decompress(data, wbits if wbits else _zlib.MAX_WBITS)
