"""A simulated device as the ev3dev drivers show it: named attributes read and written as text.

Each kind of device lists its attributes in `readers` / `writers` (name ->
method).  Errors are the OSErrors a sysfs file would give, so the shim turns
them into the exceptions python-ev3dev2 raises on a real brick.
"""

from __future__ import annotations

import errno
from collections.abc import Callable


def invalid(value: object) -> OSError:
    """The error a driver gives for a value it refuses (EINVAL)."""
    return OSError(errno.EINVAL, f"Invalid argument: {value!r}")


def parse_int(value: str) -> int:
    try:
        return int(str(value).strip())
    except ValueError:
        raise invalid(value) from None


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
        # waiting for an answer (see ev3sim2d/protocol): ["int", low, high] (None: no bound),
        # ["choice", [texts]] (compared after strip), ["any"]; a writer not listed is asked every time
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
