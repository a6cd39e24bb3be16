"""What the sensor classes share: finding the sensor, switching its mode when a method needs another one,
and reading its values, as Pybricks 2.0 does on an EV3 (pybricks-micropython v2.0.0,
bricks/ev3dev/pbdevice.c and lib/ev3dev/src/ev3dev_stretch/lego_sensor.c).

The firmware keeps one record per sensor port (pbdevice.c: `iodevices[4]`): the mode the sensor is in,
and that mode's number of values and data format.  Making a sensor object reads them from the driver
(get_device); a method that needs another mode writes `mode`, reads `num_values` and `bin_data_format`
again, and waits the sensor's mode-switch delay (get_values, get_mode_switch_delay); then every call
reads `bin_data` once and unpacks it.  So a loop that calls one method costs one read per call, and a
loop that alternates two modes pays a mode switch each time, as on a brick.
"""

import struct
import time
from errno import ENODEV

from . import _device, _link

CLASS = "lego-sensor"

# lego_sensor.c lego_sensor_get_info: the driver's bin_data_format -> how each value is stored
_FORMATS = {"u8": "B", "s8": "b", "u16": "H", "s16": "h", "s32": "i", "u32": "I", "s16_be": "h", "float": "f"}


class _PortRecord:
    """pbdevice.c `pbdevice_t`: the sensor on one port, its current mode and how to unpack its data."""

    __slots__ = ("device", "driver", "modes", "mode", "unpack", "delay_s")

    def __init__(self, device, driver, modes, delay_ms):
        self.device = device
        self.driver = driver
        self.modes = modes
        self.mode = ""
        self.unpack = None
        self.delay_s = delay_ms / 1000

    def read_info(self):
        """lego_sensor_get_info: the current mode's number of values and data format."""
        count = int(_link.read(CLASS, self.device, "num_values"))
        kind = _link.read(CLASS, self.device, "bin_data_format").strip()
        order = ">" if kind == "s16_be" else "<"
        self.unpack = struct.Struct(order + _FORMATS[kind] * count).unpack_from


def find(port, drivers):
    """(sysfs name, driver) of the sensor of one of `drivers` (None: any) on `port`: _device.find, keeping
    the driver name it read (lego_sensor.c ev3_sensor_get_id reads it once)."""
    name = _device.port_name(port, False)
    for device in _link.list_device_names(CLASS, "*", address="ev3-ports:" + name):
        driver = _link.read(CLASS, device, "driver_name").strip()
        if drivers is None or driver in drivers:
            return device, driver
    wanted = "sensor" if drivers is None else " or ".join(drivers)
    raise OSError(ENODEV, f"ENODEV: no {wanted} on {port} ({name}); check the robot file's ports")


_PORTS = {}  # sensor port name ("in1") -> its _PortRecord, shared by every object on that port


def open_port(port, drivers, delay_ms=0):
    """The record of the sensor of one of `drivers` on `port` (pbdevice_get_device): OSError(ENODEV) if
    there is none, ValueError for a motor port.  `delay_ms`: what the firmware waits after a mode switch for
    the kind of sensor the class asks for (pbdevice.c get_mode_switch_delay).  Reads the mode it is in now, as the firmware does; two
    objects on one port share one record, as they share the firmware's."""
    device, driver = find(port, drivers)
    modes = tuple(_link.read(CLASS, device, "modes").split())
    name = _device.port_name(port, False)
    record = _PORTS.get(name)
    if record is None or record.device != device:
        record = _PORTS[name] = _PortRecord(device, driver, modes, delay_ms)
    record.delay_s = delay_ms / 1000
    record.mode = _link.read(CLASS, device, "mode").strip()
    record.read_info()
    return record


def switch(record, mode):
    """pbdevice.c get_values: write the mode, read its data info, wait the sensor's switch delay."""
    _link.write(CLASS, record.device, "mode", mode)
    record.mode = mode
    record.read_info()
    if record.delay_s:
        time.sleep(record.delay_s)


def values(record, mode):
    """The values of `mode` as the firmware reads them (the raw integers of bin_data), switching first if
    the sensor is in another mode."""
    if record.mode != mode:
        switch(record, mode)
    data = _link.read(CLASS, record.device, "bin_data")
    if isinstance(data, str):
        data = data.encode("latin-1")
    return record.unpack(data)


def value(record, mode):
    """The first value of `mode` (most methods need only that)."""
    if record.mode != mode:
        switch(record, mode)
    data = _link.read(CLASS, record.device, "bin_data")
    if isinstance(data, str):
        data = data.encode("latin-1")
    return record.unpack(data)[0]


class Sensor:
    """A sensor class of the firmware: one port record, found when the object is made.  A class says the
    drivers it accepts (lego_sensor.c ev3_sensor_assert_id) and its mode-switch delay."""

    _DRIVERS = ()
    _SWITCH_DELAY_MS = 0

    def __init__(self, port):
        self._record = open_port(port, self._DRIVERS, self._SWITCH_DELAY_MS)


def mode_by_index(record, index):
    """The name of mode number `index` (the firmware's modes are numbers into the driver's list of modes);
    ValueError for a number the sensor has no mode for (lego_sensor_set_mode: PBIO_ERROR_INVALID_ARG)."""
    if not isinstance(index, int):
        raise TypeError(f"can't convert {type(index).__name__} to int")
    if index < 0 or index >= len(record.modes):
        raise ValueError("Invalid argument")
    return record.modes[index]


def absent(port, what):
    """OSError(ENODEV) for a device the simulator cannot have on `port` (ValueError for a motor port first,
    as the firmware checks the port before looking)."""
    name = _device.port_name(port, False)
    raise OSError(ENODEV, f"ENODEV: no {what} on {port} ({name}); ev3sim2d cannot simulate one")
