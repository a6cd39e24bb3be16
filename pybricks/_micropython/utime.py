"""MicroPython's `utime` as EV3 MicroPython (MicroPython v1.11, unix port with extmod/utime_mphal.c) has it.

The ticks count milliseconds or microseconds of the monotonic clock and wrap at 2**30 (the EV3's small
ints are 31 bits): compare them with ticks_diff().  In a simulated run every clock is the virtual one."""

import time as _time

_PERIOD = 1 << 30


def sleep(seconds):
    """Sleep `seconds` (a float for fractions)."""
    _time.sleep(seconds)


def sleep_ms(ms):
    """Sleep `ms` milliseconds."""
    if ms > 0:
        _time.sleep(ms / 1000)


def sleep_us(us):
    """Sleep `us` microseconds."""
    if us > 0:
        _time.sleep(us / 1_000_000)


def ticks_ms():
    """Milliseconds of the monotonic clock, wrapping at 2**30."""
    return (_time.monotonic_ns() // 1_000_000) & (_PERIOD - 1)


def ticks_us():
    """Microseconds of the monotonic clock, wrapping at 2**30."""
    return (_time.monotonic_ns() // 1_000) & (_PERIOD - 1)


ticks_cpu = ticks_us


def ticks_add(ticks, delta):
    """The ticks `delta` after (or before) `ticks`, wrapped."""
    return (ticks + delta) & (_PERIOD - 1)


def ticks_diff(end, start):
    """end - start, for ticks that may have wrapped between them."""
    return ((end - start + _PERIOD // 2) & (_PERIOD - 1)) - _PERIOD // 2


def time():
    """Seconds since 1970 (the unix port's: a float)."""
    return _time.time()


def localtime(secs=None):
    """(year, month, mday, hour, minute, second, weekday, yearday) of `secs`, or of now."""
    return tuple(_time.localtime(secs))[:8]


def mktime(t):
    """Seconds since 1970 of a localtime() tuple."""
    return int(_time.mktime(tuple(t[:8]) + (-1,)))
