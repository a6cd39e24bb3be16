"""The ev3dev2 shim: python-ev3dev2 2.1.0's API, backed by the ev3sim2d simulator.

Module for module, class for class, this package mirrors python-ev3dev2 2.1.0
(MIT licence, the ev3dev Python team), so a student's program runs unchanged.
Where the real library reads and writes sysfs attribute files, ``Device`` reads
and writes them through ``ev3dev2._link``, the only module that talks to the
simulator.  Everything above the attribute level (caching, rounding, the order
of reads and writes, exceptions and their messages) follows the real library.
"""

import errno
import fnmatch  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import io  # noqa: F401
import os
import re
import stat  # noqa: F401
import sys
from os.path import abspath  # noqa: F401

from ev3dev2 import _link
from ev3dev2.version import __version__  # noqa: F401


def is_micropython():
    return sys.implementation.name == "micropython"


def chain_exception(exception, cause):
    if is_micropython():
        raise exception
    else:
        raise exception from cause


def get_current_platform():
    """
    The simulated brick is an EV3: 'ev3', or 'fake' when the environment sets FAKE_SYS, as
    python-ev3dev2 2.1.0 answers (its own tests set it to run on a fake sysfs, where ports are
    named 'outA' and 'in1').
    """
    if os.environ.get("FAKE_SYS"):
        return "fake"
    return "ev3"


def _class_name_of(class_path):
    """'tacho-motor' from '/sys/class/tacho-motor' (or from 'tacho-motor' itself)."""
    return os.path.basename(class_path.rstrip("/"))


def list_device_names(class_path, name_pattern, **kwargs):
    """
    Generator of the names of the devices in the sysfs class ``class_path``
    (e.g. '/sys/class/tacho-motor') whose name matches ``name_pattern`` (fnmatch)
    and whose attributes contain the keyword arguments' values (for a list
    value, any one entry is enough), e.g. ``address='outA'``.
    """
    yield from _link.list_device_names(_class_name_of(class_path), name_pattern, **kwargs)


def library_load_warning_message(library_name, dependent_class):
    return f'Import warning: Failed to import "{library_name}". {dependent_class} will be unusable!'


class DeviceNotFound(Exception):
    pass


class DeviceNotDefined(Exception):
    pass


class ThreadNotRunning(Exception):
    pass


class _attribute:
    """
    A device property backed by one sysfs attribute, read and written exactly
    as upstream's hand-written properties do; the attribute's handle is kept in
    the slot named '_' + the property's name (``_speed_sp`` for ``speed_sp``).

    ``kind`` is 'int', 'string' or 'set' (a space-separated list); ``cached``
    reads the attribute once per device; a write-only attribute raises on
    reading with upstream's message.
    """

    _GETTERS = {
        ("int", False): "get_attr_int",
        ("int", True): "get_cached_attr_int",
        ("string", False): "get_attr_string",
        ("string", True): "get_cached_attr_string",
        ("set", False): "get_attr_set",
        ("set", True): "get_cached_attr_set",
    }
    _SETTERS = {"int": "set_attr_int", "string": "set_attr_string"}

    def __init__(self, sysfs_name, doc, kind="int", writable=True, readable=True, cached=False):
        self.sysfs_name = sysfs_name
        self.__doc__ = doc
        self.kind = kind
        self.getter = self._GETTERS[(kind, cached)] if readable else None
        self.setter = self._SETTERS[kind] if writable else None
        self.direct = (
            readable and kind in ("int", "string") and not cached
        )  # hot paths: read straight through
        self.name = self.slot = None

    def __set_name__(self, owner, name):
        self.name = name
        self.slot = "_" + name

    def __get__(self, device, owner=None):
        if device is None:
            return self
        if self.direct:  # what get_attr_int / get_attr_string do, without the handle bookkeeping
            try:
                value = _link.read(device._class_name, device._device_name, self.sysfs_name)
            except Exception as ex:
                device._raise_friendly_access_error(ex, self.sysfs_name, None)
            return int(value) if self.kind == "int" else value.strip()
        if self.getter is None:
            raise Exception(f"{self.name} is a write-only property!")
        handle, value = getattr(device, self.getter)(getattr(device, self.slot), self.sysfs_name)
        setattr(device, self.slot, handle)
        return value

    def __set__(self, device, value):
        if self.setter is None:
            raise AttributeError(f"property '{self.name}' of '{type(device).__name__}' object has no setter")
        text = str(int(value)) if self.kind == "int" else value
        if isinstance(text, str):  # what set_attr_int / set_attr_string do, without the handle bookkeeping
            try:
                _link.write(device._class_name, device._device_name, self.sysfs_name, text)
            except Exception as ex:
                device._raise_friendly_access_error(ex, self.sysfs_name, text.encode())
            return
        handle = getattr(device, self.setter)(getattr(device, self.slot), self.sysfs_name, value)
        setattr(device, self.slot, handle)


class Device:
    """The ev3dev device base class: one device of a sysfs class, found by name and attributes."""

    __slots__ = [
        "_path",
        "_device_index",
        "_attr_cache",
        "kwargs",
        "_class_name",
        "_device_name",
    ]

    DEVICE_ROOT_PATH = "/sys/class"

    # Greedy on purpose, as upstream: 'motor12' gives index 2.
    _DEVICE_INDEX = re.compile(r"^.*(\d+)$")

    def __init__(self, class_name, name_pattern="*", name_exact=False, **kwargs):
        """
        Find a device of sysfs class ``class_name`` (e.g. 'tacho-motor') whose
        name matches ``name_pattern`` and whose attributes match the keyword
        arguments (e.g. ``address='outA'``, ``driver_name=['lego-ev3-us',
        'lego-nxt-us']``).  With ``name_exact`` the pattern is taken as the
        device's name without looking it up.  Raises DeviceNotFound when no
        connected device matches.
        """
        self.kwargs = kwargs
        self._attr_cache = {}
        self._class_name = class_name

        def get_index(name):
            match = Device._DEVICE_INDEX.match(name)
            return int(match.group(1)) if match else None

        if name_exact:
            name = name_pattern
        else:
            name = next(iter(_link.list_device_names(class_name, name_pattern, **kwargs)), None)

        if name is None:
            self._device_name = None
            self._path = None
            self._device_index = None
            chain_exception(DeviceNotFound(f"{self} is not connected."), None)

        self._device_name = name
        self._path = Device.DEVICE_ROOT_PATH + "/" + class_name + "/" + name
        self._device_index = get_index(name)

    def __str__(self):
        if "address" in self.kwargs:
            return "{}({})".format(self.__class__.__name__, self.kwargs.get("address"))
        else:
            return self.__class__.__name__

    def __repr__(self):
        return self.__str__()

    # This allows us to sort lists of Device objects
    def __lt__(self, other):
        return str(self) < str(other)

    def _attribute_file_open(self, name):
        """There are no files here: the attribute's name stands for its open file."""
        return name

    def _get_attribute(self, attribute, name):
        """Device attribute getter: returns (handle, stripped value)."""
        try:
            value = _link.read(self._class_name, self._device_name, name)
        except Exception as ex:
            self._raise_friendly_access_error(ex, name, None)
        if attribute is None:
            attribute = self._attribute_file_open(name)
        return attribute, value.strip()

    def _set_attribute(self, attribute, name, value):
        """Device attribute setter: returns the handle."""
        if isinstance(value, str):
            value = value.encode()
        try:
            _link.write(self._class_name, self._device_name, name, value)
        except Exception as ex:
            self._raise_friendly_access_error(ex, name, value)
        if attribute is None:
            attribute = self._attribute_file_open(name)
        return attribute

    def _read_raw(self, name):
        """The attribute's bytes, unstripped (for bin_data)."""
        try:
            value = _link.read(self._class_name, self._device_name, name)
        except Exception as ex:
            self._raise_friendly_access_error(ex, name, None)
        if isinstance(value, str):
            value = value.encode("latin-1")
        return bytes(value)

    def _raise_friendly_access_error(self, driver_error, attribute, value):
        if not isinstance(driver_error, OSError):
            raise driver_error

        driver_errorno = driver_error.args[0] if is_micropython() else driver_error.errno

        if driver_errorno == errno.EINVAL:
            if attribute == "speed_sp":
                try:
                    max_speed = self.max_speed
                except (AttributeError, Exception):
                    chain_exception(
                        ValueError(f"The given speed value {value} was out of range"), driver_error
                    )
                else:
                    chain_exception(
                        ValueError(
                            f"The given speed value {value} was out of range. Max speed: +/-{max_speed}"
                        ),
                        driver_error,
                    )
            chain_exception(
                ValueError(f"One or more arguments were out of range or invalid, value {value}"), driver_error
            )
        elif driver_errorno == errno.ENODEV or driver_errorno == errno.ENOENT:
            # A missing attribute file means the device went away.
            chain_exception(DeviceNotFound(f"{self} is no longer connected"), driver_error)
        raise driver_error

    def get_attr_int(self, attribute, name):
        attribute, value = self._get_attribute(attribute, name)
        return attribute, int(value)

    def get_cached_attr_int(self, filehandle, keyword):
        value = self._attr_cache.get(keyword)

        if value is None:
            (filehandle, value) = self.get_attr_int(filehandle, keyword)
            self._attr_cache[keyword] = value

        return (filehandle, value)

    def set_attr_int(self, attribute, name, value):
        return self._set_attribute(attribute, name, str(int(value)))

    def set_attr_raw(self, attribute, name, value):
        return self._set_attribute(attribute, name, value)

    def get_attr_string(self, attribute, name):
        return self._get_attribute(attribute, name)

    def get_cached_attr_string(self, filehandle, keyword):
        value = self._attr_cache.get(keyword)

        if value is None:
            (filehandle, value) = self.get_attr_string(filehandle, keyword)
            self._attr_cache[keyword] = value

        return (filehandle, value)

    def set_attr_string(self, attribute, name, value):
        return self._set_attribute(attribute, name, value)

    def get_attr_line(self, attribute, name):
        return self._get_attribute(attribute, name)

    def get_attr_set(self, attribute, name):
        attribute, value = self.get_attr_line(attribute, name)
        return attribute, [v.strip("[]") for v in value.split()]

    def get_cached_attr_set(self, filehandle, keyword):
        value = self._attr_cache.get(keyword)

        if value is None:
            (filehandle, value) = self.get_attr_set(filehandle, keyword)
            self._attr_cache[keyword] = value

        return (filehandle, value)

    def get_attr_from_set(self, attribute, name):
        """The [bracketed] entry of a set attribute such as 'none [timer] heartbeat'."""
        attribute, value = self.get_attr_line(attribute, name)
        for a in value.split():
            v = a.strip("[]")
            if v != a:
                return v
        return ""

    @property
    def device_index(self):
        return self._device_index


def list_devices(class_name, name_pattern, **kwargs):
    """
    Generator of a ``Device`` for every device of sysfs class ``class_name``
    that matches ``name_pattern`` and the keyword arguments (as ``Device``).
    """
    return (
        Device(class_name, name, name_exact=True)
        for name in list_device_names(class_name, name_pattern, **kwargs)
    )
