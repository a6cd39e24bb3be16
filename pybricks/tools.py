"""Timing and data logging: wait, StopWatch, DataLog (pybricks.tools, Pybricks 2.0).

pybricks-micropython v2.0.0: wait and StopWatch are written in C (extmod/modtools.c), counting in whole
milliseconds of the brick's monotonic clock (mp_hal_ticks_ms); DataLog is Python
(bricks/ev3dev/modules/pybricks/tools.py).  `print` is here too, as EV3 MicroPython 1.0 had it.  In a
simulated run every clock is the virtual one, so waits and stopwatches follow the simulation.
"""

import time as _time
from builtins import print  # noqa: A004 - 1.0 programs import print from pybricks.tools

from ._arguments import get_int

__all__ = ["print", "wait", "StopWatch", "DataLog"]


def _ticks_ms():
    """mp_hal_ticks_ms: milliseconds of the monotonic clock."""
    return _time.monotonic_ns() // 1_000_000


def _ticks_us():
    return _time.monotonic_ns() // 1_000


def wait(time):
    """Wait `time` ms (floats truncated toward zero; 0 or less returns at once)."""
    duration = get_int(time)
    if duration > 0:
        _time.sleep(duration / 1000)


_MASK = 0xFFFFFFFF  # the firmware keeps a stopwatch's times in uint32_t


class StopWatch:
    """A stopwatch that starts when it is made: time() in ms, pause(), resume(), reset()."""

    def __init__(self):
        self.reset()
        self._running = False
        self.resume()

    def reset(self):
        """Set the time back to 0; a paused stopwatch stays paused."""
        self._start = _ticks_ms() & _MASK
        self._stop = self._start
        self._pausing = 0

    def time(self):
        """The time in ms, without the time spent paused."""
        end = _ticks_ms() if self._running else self._stop
        return (end - self._start - self._pausing) & _MASK

    def pause(self):
        """Stop counting."""
        if self._running:
            self._running = False
            self._stop = _ticks_ms() & _MASK

    def resume(self):
        """Count on from the time it was paused at."""
        if not self._running:
            self._running = True
            self._pausing = (self._pausing + _ticks_ms() - self._stop) & _MASK

    def __repr__(self):
        return "<StopWatch>"


class DataLog:
    """A CSV file to log values in: DataLog(*headers, name='log', timestamp=True, extension='csv',
    append=False) writes `name_yyyy_mm_dd_hh_mm_ss_uuuuuu.csv` in the program's folder."""

    def __init__(self, *headers, name="log", timestamp=True, extension="csv", append=False):
        if timestamp:
            y, mo, d, h, mi, s = _time.localtime()[0:6]
            u = _ticks_us() % 1000000
            stamp = f"_{y}_{mo:02d}_{d:02d}_{h:02d}_{mi:02d}_{s:02d}_{u:06d}"
        else:
            stamp = ""
        mode = "a+" if append else "w+"
        self.file = open(f"{name}{stamp}.{extension}", mode, buffering=1)
        self.file.seek(0, 2)
        length = self.file.tell()
        if len(headers) > 0 and length == 0:
            print(*headers, sep=", ", file=self.file)

    def log(self, *values):
        """Write a line of `values`, separated by ', '."""
        print(*values, sep=", ", file=self.file)

    def __repr__(self):
        self.file.seek(0, 0)
        return self.file.read()
