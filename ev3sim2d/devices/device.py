"""A simulated device as the ev3dev drivers show it: named attributes read and written as text.

Each kind of device lists its attributes in `readers` / `writers` (name ->
method).  Errors are the OSErrors a sysfs file would give, so the shim turns
them into the exceptions python-ev3dev2 raises on a real brick.
"""

from __future__ import annotations

import errno
from collections.abc import Callable

C_INT_MIN = -(2**31)  # the drivers parse integer attributes into a C int (kstrtoint): 32 bits on the EV3
C_INT_MAX = 2**31 - 1
C_ULONG_MAX = 2**32 - 1  # ... or an unsigned long (kstrtoul: the LED class's brightness), 32 bits there too
PAGE_BYTES = 4096  # sysfs hands a driver's store at most one page of what was written


def invalid(value: object) -> OSError:
    """The error a driver gives for a value it refuses (EINVAL); the value shown is cut short, as a value
    a brick sends may be megabytes long."""
    shown = repr(value) if not isinstance(value, str) or len(value) <= 40 else repr(value[:40]) + "..."
    return OSError(errno.EINVAL, f"Invalid argument: {shown}")


def int_rule(low: int = C_INT_MIN, high: int = C_INT_MAX) -> list:
    """An integer attribute's write rule (Device.write_rules): the attribute's own range where its driver
    has one, else the C type's the driver parses it into; never unbounded."""
    return ["int", low, high]


def parse_int(value: str, low: int = C_INT_MIN, high: int = C_INT_MAX) -> int:
    """A written integer as a driver parses it: a number within [low, high], by default a C int's range
    (a 4000-digit gain is refused here, not found out inside the world's tick); EINVAL otherwise.  Accepts what the brick's own check accepts (brick/link.py check_write: Python's int()
    of the stripped text), so that both refuse exactly the same values."""
    text = str(value).strip()
    if len(text) > PAGE_BYTES:  # (and never hand int() megabytes: its cost grows with the square)
        raise invalid(value)
    try:
        number = int(text)
    except ValueError:
        raise invalid(value) from None
    if not low <= number <= high:
        raise invalid(value)
    return number


class Device:
    """Base of every simulated device: attribute access by name, as in /sys/class."""

    sysfs_class = ""  # 'tacho-motor', 'lego-sensor', ...
    name_prefix = ""  # device names are prefix + index: motor0, sensor2

    def __init__(self, address: str, driver_name: str) -> None:
        self.address = address
        self.driver_name = driver_name
        self.readers: dict[str, Callable[[], str]] = {
            "address": lambda: self.address,
            "driver_name": lambda: self.driver_name,
        }
        self.writers: dict[str, Callable[[str], None]] = {}
        # what each writer accepts, so that a brick can check a write itself and send it on without
        # waiting for an answer (see ev3sim2d/protocol): ["int", low, high] (int_rule: never wider than
        # a C int, as the drivers parse them), ["choice", [texts]] (compared after strip), ["any"]; a
        # writer not listed is asked every time.  A writer raises nothing but OSError, whatever the text
        self.write_rules: dict[str, list] = {}
        # how often a brick must ask for an attribute's value: a constant once; a setting again only
        # after the program wrote to the device; any other attribute changes with the world (each tick)
        self.constants: set[str] = {"address", "driver_name"}
        self.settings: set[str] = set()

    def read(self, attribute: str) -> str:
        reader = self.readers.get(attribute)
        if reader is None:
            if attribute in self.writers:
                raise OSError(errno.EACCES, f"{attribute} is write-only")
            raise OSError(errno.ENOENT, f"No such attribute: {attribute}")
        return reader()

    def write(self, attribute: str, value: str) -> None:
        writer = self.writers.get(attribute)
        if writer is None:
            if attribute in self.readers:
                raise OSError(errno.EACCES, f"{attribute} is read-only")
            raise OSError(errno.ENOENT, f"No such attribute: {attribute}")
        writer(value)
