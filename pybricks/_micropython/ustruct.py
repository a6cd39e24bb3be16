"""MicroPython's `ustruct`: calcsize, pack, pack_into, unpack, unpack_from (CPython's struct)."""

from struct import calcsize, pack, pack_into, unpack, unpack_from  # noqa: F401
