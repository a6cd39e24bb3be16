"""LEGO MINDSTORMS NXT sensors on the EV3 (pybricks.nxtdevices, Pybricks 2.0).

As pybricks-micropython v2.0.0 has them for the EV3: extmod/modnxtdevices.c (TouchSensor, SoundSensor,
LightSensor, UltrasonicSensor, ColorSensor, TemperatureSensor, EnergyMeter) and
bricks/ev3dev/modules/pybricks/nxtdevices.py (VernierAdapter).  The simulator has NXT light and sound
sensors (ev3sim2d/devices/nxt_light.py, nxt_sound.py); the other classes find nothing of their kind on
a simulated robot and raise OSError(ENODEV) when made, as the firmware does for a port without one.
"""

from . import _sensor
from .iodevices import AnalogSensor


def _analog_scale(mvolts, mvolts_min, mvolts_max, invert):
    """modnxtdevices.c analog_scale: millivolts to 0-100 %, in C's integer arithmetic (toward zero)."""
    numerator = 100 * (mvolts - mvolts_min)
    span = mvolts_max - mvolts_min
    scaled = abs(numerator) // abs(span) * (1 if (numerator >= 0) == (span > 0) else -1)
    if invert:
        scaled = 100 - scaled
    return max(0, min(scaled, 100))


class TouchSensor(_sensor.Sensor):
    """LEGO MINDSTORMS NXT Touch Sensor (pressed while its pin reads below 2500 mV)."""

    _DRIVERS = ("lego-nxt-touch", "nxt-analog")

    def pressed(self):
        """True while the sensor is pressed."""
        return _sensor.value(self._record, self._record.modes[0]) < 2500


class SoundSensor(_sensor.Sensor):
    """LEGO MINDSTORMS NXT Sound Sensor.

    The firmware reads the nxt-analog driver (ev3dev cannot tell an NXT sound sensor from other analog
    sensors); the simulator's is the lego-nxt-sound driver, whose two modes (DB, DBA) have the same pin-5
    states as nxt-analog's mode 0 (passive) and 1 (active) that the firmware uses."""

    _DRIVERS = ("nxt-analog", "lego-nxt-sound")
    _SWITCH_DELAY_MS = 300  # pbdevice.c get_mode_switch_delay, PBIO_IODEV_TYPE_ID_NXT_SOUND_SENSOR

    def __init__(self, port):
        super().__init__(port)
        self.intensity()  # (the firmware reads once, "for consistent initial mode")

    def intensity(self, audible_only=True):
        """Ambient sound intensity (loudness), 0 to 100 %: an int."""
        record = self._record
        analog = _sensor.value(record, record.modes[1 if audible_only else 0])
        if record.driver == "lego-nxt-sound":
            # the simulated sensor's bin_data rises with loudness (0 to 5000 mV for 0 to 100 %, the
            # lego-nxt-sound driver's raw scale); a real NXT sound sensor's voltage falls as it gets louder,
            # from 4860 mV (quiet) to 650 mV (loud), as the firmware's scale has it: the voltage it would give
            analog = 4860 - analog * (4860 - 650) // 5000
        return _analog_scale(analog, 650, 4860, True)


class LightSensor(_sensor.Sensor):
    """LEGO MINDSTORMS NXT Light Sensor."""

    _DRIVERS = ("lego-nxt-light",)
    _SWITCH_DELAY_MS = 20  # pbdevice.c get_mode_switch_delay

    def __init__(self, port):
        super().__init__(port)
        self.reflection()  # (the firmware reads once "to ensure a consistent initial mode")

    def ambient(self):
        """Ambient light intensity, 0 to 100 %: an int (the AMBIENT millivolts, 4164 dark to 1906 bright)."""
        return _analog_scale(_sensor.value(self._record, "AMBIENT"), 1906, 4164, True)

    def reflection(self):
        """Reflected light intensity, 0 to 100 %: an int (the REFLECT millivolts, 3000 dark to 1906 bright)."""
        return _analog_scale(_sensor.value(self._record, "REFLECT"), 1906, 3000, True)


class UltrasonicSensor(_sensor.Sensor):
    """LEGO MINDSTORMS NXT Ultrasonic Sensor."""

    _DRIVERS = ("lego-nxt-us",)

    def distance(self):
        """Distance in mm (the sensor measures whole cm)."""
        return _sensor.value(self._record, self._record.modes[0]) * 10


class ColorSensor:
    """LEGO MINDSTORMS NXT Color Sensor.  The firmware drives it through the port's raw mode
    (lib/ev3dev/src/ev3dev_stretch/nxtcolor.c), which the simulator has no device for."""

    def __init__(self, port):
        _sensor.absent(port, "NXT Color Sensor")

    def all(self):
        """(red, green, blue, ambient, color)."""

    def rgb(self):
        """(red, green, blue) reflection, each 0 to 100."""

    def ambient(self):
        """Ambient light, 0 to 100."""

    def reflection(self):
        """The mean of the red, green and blue reflection."""

    def color(self):
        """The colour seen: a Color or None."""


class TemperatureSensor(_sensor.Sensor):
    """LEGO MINDSTORMS NXT Temperature Sensor."""

    _DRIVERS = ("lego-nxt-temp",)

    def temperature(self):
        """The temperature in degrees Celsius: a float."""
        return (_sensor.value(self._record, self._record.modes[0]) >> 4) / 16.0


class EnergyMeter(_sensor.Sensor):
    """LEGO MINDSTORMS Education NXT Energy Meter."""

    _DRIVERS = ("lego-power-storage",)
    _SWITCH_DELAY_MS = 200  # pbdevice.c get_mode_switch_delay

    def __init__(self, port):
        super().__init__(port)
        self._all()  # (the firmware reads once, to be in the mode every method uses)

    def _all(self):
        record = self._record
        return _sensor.values(record, _sensor.mode_by_index(record, 7))

    def storage(self):
        """The energy stored, in J."""
        return self._all()[4]

    def input(self):
        """(voltage mV, current mA, power mW) at the input."""
        data = self._all()
        return (data[0], data[1], data[5])

    def output(self):
        """(voltage mV, current mA, power mW) at the output."""
        data = self._all()
        return (data[2], data[3], data[6])


class VernierAdapter(AnalogSensor):
    """LEGO MINDSTORMS Education NXT/EV3 Adapter for Vernier Sensors: an AnalogSensor whose value() is
    conversion(voltage()) (bricks/ev3dev/modules/pybricks/nxtdevices.py)."""

    def __init__(self, port, conversion=None):
        super().__init__(port)
        if conversion is not None:
            self.conversion = conversion
        try:
            for volts in (0, 10, 1000, 3000, 5000):
                self.conversion(volts)
        except Exception:
            print(
                "\nThere is an error in the conversion function. Make sure it has the following form:\n"
                "\ndef my_conversion_function(voltage):"
                "\n    value = voltage * 3  # This is just an example. Use your own formula here."
                "\n    return value\n"
                "\nThe technical description of the error is as follows:\n"
            )
            raise

    def conversion(self, voltage):
        return voltage

    def value(self):
        return self.conversion(self.voltage())


__all__ = [
    "TouchSensor",
    "SoundSensor",
    "LightSensor",
    "UltrasonicSensor",
    "ColorSensor",
    "TemperatureSensor",
    "EnergyMeter",
    "VernierAdapter",
]
