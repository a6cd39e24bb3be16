"""Generic input/output devices on the EV3 (pybricks.iodevices, Pybricks 2.0).

As pybricks-micropython v2.0.0 has them for the EV3 (extmod/modiodevices.c, re-exported by
bricks/ev3dev/modules/pybricks/iodevices.py): Ev3devSensor (any ev3dev lego-sensor, by mode name) and
LUMPDevice (an EV3 UART sensor, by mode number) work with every simulated sensor they accept;
AnalogSensor, I2CDevice and UARTDevice need devices the simulator does not have, so making one raises
OSError(ENODEV).  DCMotor is the motor module's (pybricks/_motor.py).
"""

from errno import EOPNOTSUPP

from . import _sensor
from ._motor import DCMotor  # noqa: F401 - (modmotor.c motor_DCMotor_type, listed in modiodevices.c)

# the drivers of EV3 UART sensors (LUMP): lego_port.c configures the port as ev3-uart for a LUMPDevice
_UART_DRIVERS = ("lego-ev3-color", "lego-ev3-us", "lego-ev3-gyro", "lego-ev3-ir")


class LUMPDevice(_sensor.Sensor):
    """An EV3 UART sensor read by mode number (the driver's order of modes)."""

    _DRIVERS = _UART_DRIVERS

    def read(self, mode):
        """The values of mode number `mode`: a tuple of ints."""
        record = self._record
        return tuple(_sensor.values(record, _sensor.mode_by_index(record, mode)))

    def write(self, mode, data):
        """Not supported on the EV3 (pbdevice.c pbdevice_set_values): OSError(EOPNOTSUPP)."""
        if len(data) > 32:
            raise ValueError("Invalid argument")
        raise OSError(EOPNOTSUPP, "EOPNOTSUPP: the EV3 cannot write to a sensor's mode")


class Ev3devSensor(_sensor.Sensor):
    """Any ev3dev lego-sensor, read by the name of its mode (e.g. "COL-REFLECT").

    sensor_index and port_index are the numbers of its /sys/class/lego-sensor/sensorN and
    /sys/class/lego-port/portN folders."""

    _DRIVERS = None  # any lego-sensor (lego_sensor.c ev3_sensor_assert_id: EV3DEV_LEGO_SENSOR)

    def __init__(self, port):
        super().__init__(port)
        name = self._record.device
        self.sensor_index = int(name[len(name.rstrip("0123456789")) :] or 0)
        self.port_index = int(_sensor._device.port_name(port, False)[2:]) - 1

    def read(self, mode):
        """The values of the mode named `mode`: a tuple of ints; ValueError for a mode it does not have."""
        if not isinstance(mode, str):
            raise TypeError(f"can't convert '{type(mode).__name__}' object to str implicitly")
        record = self._record
        if mode not in record.modes:
            raise ValueError("Invalid argument")
        return tuple(_sensor.values(record, mode))


class AnalogSensor:
    """A generic analog sensor (the nxt-analog driver): voltage and resistance of its pin."""

    def __init__(self, port):
        self._record = _sensor.open_port(port, ("nxt-analog",))
        self._active = False
        _sensor.value(self._record, self._record.modes[0])  # (the firmware starts it passive)

    def _voltage(self):
        record = self._record
        return _sensor.value(record, record.modes[1 if self._active else 0])

    def voltage(self):
        """The voltage of the pin, in mV."""
        return self._voltage()

    def resistance(self):
        """The resistance between the pin and ground, in ohms (as a divider with the 10 kOhm inside)."""
        volts = self._voltage()
        vmax = 4972
        if volts >= vmax:
            return 2**31 - 1
        numerator = 10000 * volts
        return int(numerator / (vmax - volts))

    def active(self):
        """Set the sensor's pin 5 high (an NXT light sensor's LED on)."""
        _sensor.value(self._record, self._record.modes[1])
        self._active = True

    def passive(self):
        """Set the sensor's pin 5 low."""
        _sensor.value(self._record, self._record.modes[0])
        self._active = False


class I2CDevice:
    """A generic I2C device on a sensor port (its bus and address)."""

    def __init__(self, port, address):
        if not isinstance(address, int):
            raise TypeError(f"can't convert {type(address).__name__} to int")
        if address < 0 or address > 255:
            raise ValueError("Invalid argument")
        _sensor.absent(port, "I2C device")

    def read(self, reg, length=1):
        """`length` bytes from register `reg`."""

    def write(self, reg, data=None):
        """Write `data` (bytes) to register `reg`."""


class UARTDevice:
    """A generic UART device on a sensor port."""

    def __init__(self, port, baudrate, timeout=None):
        _sensor.absent(port, "UART device")

    def read(self, length=1):
        """`length` bytes, waiting up to the timeout for them."""

    def read_all(self):
        """Every byte waiting."""

    def write(self, data):
        """Write `data` (bytes)."""

    def waiting(self):
        """How many bytes are waiting to be read."""

    def clear(self):
        """Throw away the bytes waiting."""


__all__ = ["LUMPDevice", "AnalogSensor", "I2CDevice", "UARTDevice", "Ev3devSensor", "DCMotor"]
