"""The generic sensor classes (python-ev3dev2 2.1.0); the LEGO sensors are in ev3dev2.sensor.lego."""

import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
from os.path import abspath  # noqa: F401
from struct import unpack

from ev3dev2 import Device, _attribute, get_current_platform, list_device_names
from ev3dev2._platform.ev3 import INPUT_1, INPUT_2, INPUT_3, INPUT_4  # noqa: F401

platform = get_current_platform()
if platform == "fake":
    from ev3dev2._platform.fake import INPUT_1, INPUT_2, INPUT_3, INPUT_4  # noqa: F401


class Sensor(Device):
    """A sensor of the ``lego-sensor`` class: modes, raw values and their scaling."""

    SYSTEM_CLASS_NAME = "lego-sensor"
    SYSTEM_DEVICE_NAME_CONVENTION = "sensor*"
    __slots__ = [
        "_address",
        "_command",
        "_commands",
        "_decimals",
        "_driver_name",
        "_mode",
        "_modes",
        "_num_values",
        "_units",
        "_value",
        "_bin_data_format",
        "_bin_data_size",
        "_bin_data",
        "_mode_scale",
    ]

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._address = None
        self._command = None
        self._commands = None
        self._decimals = None
        self._driver_name = None
        self._mode = None
        self._modes = None
        self._num_values = None
        self._units = None
        self._value = [None, None, None, None, None, None, None, None]

        self._bin_data_format = None
        self._bin_data_size = None
        self._bin_data = None
        self._mode_scale = {}

    def _scale(self, mode):
        """The scaling factor of values in ``mode`` (10 ** -decimals), read once per mode key."""
        if mode in self._mode_scale:
            scale = self._mode_scale[mode]
        else:
            scale = 10 ** (-self.decimals)
            self._mode_scale[mode] = scale

        return scale

    address = _attribute(
        "address",
        "The port the sensor is connected to, e.g. ``ev3-ports:in1``.",
        kind="string",
        writable=False,
    )
    command = _attribute("command", "Sends a command to the sensor.", kind="string", readable=False)
    commands = _attribute(
        "commands", "The commands the sensor supports.", kind="set", writable=False, cached=True
    )
    decimals = _attribute(
        "decimals",
        "The number of decimal places of the ``value<N>`` attributes in this mode.",
        writable=False,
    )
    driver_name = _attribute(
        "driver_name",
        "The name of the sensor's driver, e.g. ``lego-ev3-color``.",
        kind="string",
        writable=False,
        cached=True,
    )
    mode = _attribute("mode", "The current mode; writing one of ``modes`` switches to it.", kind="string")
    modes = _attribute("modes", "The modes the sensor supports.", kind="set", writable=False, cached=True)
    num_values = _attribute(
        "num_values", "How many ``value<N>`` attributes are valid in this mode.", writable=False
    )
    units = _attribute(
        "units", "The units of the values in this mode (may be empty).", kind="string", writable=False
    )

    def value(self, n=0):
        """
        The raw value number ``n`` measured by the sensor (see ``num_values``);
        a fixed-point number: divide by 10 ** ``decimals`` for the actual value.
        """
        n = int(n)

        self._value[n], value = self.get_attr_int(self._value[n], "value" + str(n))
        return value

    bin_data_format = _attribute(
        "bin_data_format",
        """
        The format of ``bin_data`` in this mode: ``u8``, ``s8``, ``u16``, ``s16``,
        ``s16_be``, ``s32`` or ``float``.
        """,
        kind="string",
        writable=False,
    )

    def bin_data(self, fmt=None):
        """
        The raw values as a bytearray, or unpacked with the struct format ``fmt``.

        Example::

            >>> ir.value()
            28
            >>> ir.bin_data('<b')
            (28,)
        """
        if self._bin_data_size is None:
            self._bin_data_size = {
                "u8": 1,
                "s8": 1,
                "u16": 2,
                "s16": 2,
                "s16_be": 2,
                "s32": 4,
                "float": 4,
            }.get(self.bin_data_format, 1) * self.num_values

        if self._bin_data is None:
            self._bin_data = self._attribute_file_open("bin_data")

        raw = bytearray(self._read_raw("bin_data")[: self._bin_data_size])

        if fmt is None:
            return raw

        return unpack(fmt, raw)

    def _ensure_mode(self, mode):
        if self.mode != mode:
            self.mode = mode


def list_sensors(name_pattern=Sensor.SYSTEM_DEVICE_NAME_CONVENTION, **kwargs):
    """
    Generator of a ``Sensor`` for every sensor matching ``name_pattern`` and the
    keyword arguments, e.g. ``driver_name='lego-ev3-touch'`` or ``address=['in1', 'in3']``.
    """
    return (
        Sensor(name_pattern=name, name_exact=True)
        for name in list_device_names(Sensor.SYSTEM_CLASS_NAME, name_pattern, **kwargs)
    )


class I2cSensor(Sensor):
    """A generic I2C (NXT-style) sensor."""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = "sensor*"

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name=["nxt-i2c-sensor"], **kwargs)
        self._fw_version = None
        self._poll_ms = None

    fw_version = _attribute(
        "fw_version",
        "The sensor's firmware version, if available (I2C/NXT sensors).",
        kind="string",
        writable=False,
        cached=True,
    )
    poll_ms = _attribute("poll_ms", "The polling period in milliseconds (0 disables polling; minimum 50).")
