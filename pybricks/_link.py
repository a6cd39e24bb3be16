"""The one place where the Pybricks shim talks to the simulator.

On a real EV3, Pybricks 2.0 drives the ev3dev drivers through their files under /sys/class
(pybricks-micropython v2.0.0: lib/ev3dev/src/ev3dev_stretch/, lib/pbio/drv/ev3dev_stretch/).  Here the
same reads and writes go to the simulated brick through the backend the brick installs with
`connect()` before the program starts: the same backend, and so the same devices, as the ev3dev2
shim's (ev3dev2/_link.py says what a backend provides).  Every other module of the shim uses only
the functions below, so the shim imports anywhere and fails only when a device is used outside a run.
"""

_backend = None

OUTSIDE_MESSAGE = (
    "this program uses EV3 devices, so it must run inside the simulator: ev3sim2d run main.py --maze empty"
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
    """Names of the devices of a sysfs class whose attributes match (e.g. address="ev3-ports:outA")."""
    return _require().list_device_names(class_name, name_pattern, match)


def _read_outside(class_name, device_name, attribute):
    raise NotInSimulation(OUTSIDE_MESSAGE)


def _write_outside(class_name, device_name, attribute, value):
    raise NotInSimulation(OUTSIDE_MESSAGE)


read = _read_outside  # read(class_name, device_name, attribute) -> str
write = _write_outside  # write(class_name, device_name, attribute, value: str) -> None


def poll(class_name, device_name, attribute, timeout_ms):
    """Wait until the attribute's value changes or timeout_ms (virtual) passes."""
    _require().poll(class_name, device_name, attribute, timeout_ms)


def call(feature, *args):
    """Brick features that are not sysfs attributes (sound, buttons, the LCD, messaging)."""
    return _require().call(feature, *args)


def tick_us() -> int:
    """The world's step in virtual microseconds: writes made within one step take effect together, as
    the firmware's control loop starts both wheels of a drive base in one step."""
    return _require().tick_us
