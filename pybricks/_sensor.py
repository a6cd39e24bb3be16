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

# pbdevice.c get_mode_switch_delay: milliseconds waited after a mode switch, by driver (0 for the others)
SWITCH_DELAY_MS = {
    "lego-ev3-color": 30,
    "lego-ev3-ir": 1100,
    "lego-nxt-light": 20,
    "lego-nxt-sound": 300,
    "nxt-analog": 300,  # (an NXT sound sensor without auto-detection is an nxt-analog)
    "lego-power-storage": 200,
}


class _PortRecord:
    """pbdevice.c `pbdevice_t`: the sensor on one port, its current mode and how to unpack its data."""

    __slots__ = ("device", "driver", "modes", "mode", "unpack", "delay_s")

    def __init__(self, device, driver, modes):
        self.device = device
        self.driver = driver
        self.modes = modes
        self.mode = ""
        self.unpack = None
        self.delay_s = SWITCH_DELAY_MS.get(driver, 0) / 1000

    def read_info(self):
        """lego_sensor_get_info: the current mode's number of values and data format."""
        count = int(_link.read(CLASS, self.device, "num_values"))
        kind = _link.read(CLASS, self.device, "bin_data_format").strip()
        order = ">" if kind == "s16_be" else "<"
        self.unpack = struct.Struct(order + _FORMATS[kind] * count).unpack_from


def find(port, drivers):
    """(sysfs name, driver) of the sensor of one of `drivers` on `port`: _device.find, keeping the driver
    name it read (lego_sensor.c ev3_sensor_get_id reads it once)."""
    name = _device.port_name(port, False)
    for device in _link.list_device_names(CLASS, "*", address="ev3-ports:" + name):
        driver = _link.read(CLASS, device, "driver_name").strip()
        if driver in drivers:
            return device, driver
    raise OSError(
        ENODEV, f"ENODEV: no {' or '.join(drivers)} on {port} ({name}); check the robot file's ports"
    )


_PORTS = {}  # sensor port name ("in1") -> its _PortRecord, shared by every object on that port


def open_port(port, drivers):
    """The record of the sensor of one of `drivers` on `port` (pbdevice_get_device): OSError(ENODEV) if
    there is none, ValueError for a motor port.  Reads the mode it is in now, as the firmware does; two
    objects on one port share one record, as they share the firmware's."""
    device, driver = find(port, drivers)
    modes = tuple(_link.read(CLASS, device, "modes").split())
    name = _device.port_name(port, False)
    record = _PORTS.get(name)
    if record is None or record.device != device:
        record = _PORTS[name] = _PortRecord(device, driver, modes)
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
    """A sensor class of the firmware: one port record, found when the object is made."""

    _DRIVERS = ()

    def __init__(self, port):
        self._record = open_port(port, self._DRIVERS)
