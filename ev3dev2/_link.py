"""The one place where the ev3dev2 shim talks to the simulator.

On a real EV3, python-ev3dev2 reads and writes files under /sys/class (the
ev3dev drivers' attributes).  In ev3sim2d the same reads and writes go to a
simulated brick through a *backend* that the simulator installs with
`connect()` when a program starts, and removes with `disconnect()` when it ends.
Every other shim module uses only the functions below, so the shim can be
imported anywhere (editors, documentation tools, tests) and fails only when a
device is actually used outside a simulated run.

A backend provides:

    list_device_names(class_name, name_pattern, match) -> list[str]
    read(class_name, device_name, attribute) -> str
    write(class_name, device_name, attribute, value: str) -> None
    poll(class_name, device_name, attribute, timeout_ms) -> None
    call(feature, *args) -> object   # brick features that are not sysfs files

Reads and writes raise OSError with the errno a sysfs file would give
(EINVAL for a value out of range, ENOENT for an attribute the driver lacks),
and cost the virtual time a real EV3 would spend on them.  Values are written
as str (bytes are decoded as latin-1 first).  While connected, `read` and
`write` *are* the backend's methods: they are called in every loop of every
program, so they go straight through.
"""

_backend = None

OUTSIDE_MESSAGE = (
    "this program uses EV3 devices, so it must run inside the simulator: ev3sim2d run PROGRAM.py --maze empty"
)


class NotInSimulation(RuntimeError):
    """A device was used outside a simulated run."""


def connect(backend) -> None:
    global _backend, read, write
    _backend = backend
    read, write = backend.read, backend.write


def disconnect() -> None:
    global _backend, read, write
    _backend = None
    read, write = _read_outside, _write_outside


def connected() -> bool:
    return _backend is not None


def _require():
    if _backend is None:
        raise NotInSimulation(OUTSIDE_MESSAGE)
    return _backend


def list_device_names(class_name, name_pattern="*", **match):
    """Names of the devices of a sysfs class whose attributes match (as python-ev3dev2 matches)."""
    return _require().list_device_names(class_name, name_pattern, match)


def _read_outside(class_name, device_name, attribute):
    raise NotInSimulation(OUTSIDE_MESSAGE)


def _write_outside(class_name, device_name, attribute, value):
    raise NotInSimulation(OUTSIDE_MESSAGE)


read = _read_outside  # read(class_name, device_name, attribute) -> str
write = _write_outside  # write(class_name, device_name, attribute, value: str | bytes) -> None


def poll(class_name, device_name, attribute, timeout_ms):
    """Wait until the attribute's value changes or timeout_ms (virtual) passes, like select.poll."""
    _require().poll(class_name, device_name, attribute, timeout_ms)


def call(feature, *args):
    """Brick features that are not sysfs attributes (sound, buttons, the LCD)."""
    return _require().call(feature, *args)
