"""A StopWatch for timing the gaps between events (python-ev3dev2 2.1.0)."""

import datetime as dt  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import time

from ev3dev2 import is_micropython  # noqa: F401


def get_ticks_ms():
    """Milliseconds since the epoch, from the (virtual, inside a run) clock of the `time` module."""
    return int(time.time() * 1000)


class StopWatchAlreadyStartedException(Exception):
    """start() was called on a StopWatch that is already running."""

    pass


class StopWatch:
    """A timer: start it, then ask how much time has elapsed."""

    def __init__(self, desc=None):
        """Initializes the StopWatch (stopped); ``desc`` is printed by str()."""
        self.desc = desc
        self._start_time = None
        self._stopped_total_time = None

    def __str__(self):
        name = self.desc if self.desc is not None else self.__class__.__name__
        return f"{name}: {self.hms_str}"

    def start(self):
        """
        Starts the timer.

        Raises a :py:class:`ev3dev2.stopwatch.StopWatchAlreadyStartedException` if already started.
        """
        if self.is_started:
            raise StopWatchAlreadyStartedException()

        self._stopped_total_time = None
        self._start_time = get_ticks_ms()

    def stop(self):
        """Stops the timer; its value is kept and stops increasing."""
        if self._start_time is None:
            return

        self._stopped_total_time = get_ticks_ms() - self._start_time
        self._start_time = None

    def reset(self):
        """Resets the timer and leaves it stopped."""
        self._start_time = None
        self._stopped_total_time = None

    def restart(self):
        """Resets and then starts the timer."""
        self.reset()
        self.start()

    @property
    def is_started(self):
        """True if the StopWatch has been started and not stopped."""
        return self._start_time is not None

    @property
    def value_ms(self):
        """The value of the stopwatch in milliseconds."""
        if self._stopped_total_time is not None:
            return self._stopped_total_time

        return get_ticks_ms() - self._start_time if self._start_time is not None else 0

    @property
    def value_secs(self):
        """The value of the stopwatch in seconds."""
        return self.value_ms / 1000

    @property
    def value_hms(self):
        """The elapsed time as a tuple ``(hours, minutes, seconds, milliseconds)``."""
        (hours, x) = divmod(int(self.value_ms), 3600000)
        (mins, x) = divmod(x, 60000)
        (secs, x) = divmod(x, 1000)
        return hours, mins, secs, x

    @property
    def hms_str(self):
        """The elapsed time as HH:MM:SS.msec."""
        hours, mins, secs, msecs = self.value_hms
        return f"{hours:02d}:{mins:02d}:{secs:02d}.{msecs:03d}"

    def is_elapsed_ms(self, duration_ms):
        """True if at least ``duration_ms`` milliseconds have elapsed (False if it is None)."""
        return duration_ms is not None and self.value_ms >= duration_ms

    def is_elapsed_secs(self, duration_secs):
        """True if at least ``duration_secs`` seconds have elapsed (False if it is None)."""
        return duration_secs is not None and self.value_secs >= duration_secs
