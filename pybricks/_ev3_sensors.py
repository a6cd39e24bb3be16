"""The EV3 sensors of pybricks.ev3devices, as pybricks-micropython v2.0.0 has them (extmod/modev3devices.c).

Each method reads its mode's values as the firmware does (pbdevice_get_values: the mode switched only
when it is another one, then one read of bin_data; _sensor.py), and turns them into what the firmware
returns: ints, bools, a Color or None, a list of Buttons.
"""

from . import _sensor
from ._arguments import get_int
from .parameters import Button, Color, Direction

# modev3devices.c ev3devices_ColorSensor_color: the driver's colour numbers -> Color (0 and others: None)
_COLORS = {
    1: Color.BLACK,
    2: Color.BLUE,
    3: Color.GREEN,
    4: Color.YELLOW,
    5: Color.RED,
    6: Color.WHITE,
    7: Color.BROWN,
}

# modev3devices.c ev3devices_InfraredSensor_buttons: IR-REMOTE's code of a channel -> the buttons pressed
_REMOTE = {
    0: [],
    1: [Button.LEFT_UP],
    2: [Button.LEFT_DOWN],
    3: [Button.RIGHT_UP],
    4: [Button.RIGHT_DOWN],
    5: [Button.LEFT_UP, Button.RIGHT_UP],
    6: [Button.LEFT_UP, Button.RIGHT_DOWN],
    7: [Button.LEFT_DOWN, Button.RIGHT_UP],
    8: [Button.LEFT_DOWN, Button.RIGHT_DOWN],
    9: [Button.BEACON],
    10: [Button.LEFT_UP, Button.LEFT_DOWN],
    11: [Button.RIGHT_UP, Button.RIGHT_DOWN],
}
# ev3devices_InfraredSensor_keypad: IR-REM-A's bits -> buttons (384: nothing pressed)
_KEYPAD = (
    (0x10, Button.LEFT_UP),
    (0x20, Button.LEFT_DOWN),
    (0x40, Button.RIGHT_UP),
    (0x80, Button.RIGHT_DOWN),
)


def _channel(channel):
    """A remote's channel, 1 to 4; anything else is ValueError (pb_assert(PBIO_ERROR_INVALID_ARG))."""
    number = get_int(channel)
    if number < 1 or number > 4:
        raise ValueError("channel must be 1, 2, 3 or 4")
    return number


class TouchSensor(_sensor.Sensor):
    """LEGO MINDSTORMS EV3 Touch Sensor."""

    _DRIVERS = ("lego-ev3-touch",)

    def pressed(self):
        """True while the sensor is pressed.

        The firmware reads TOUCH's bin_data, on a brick the sensor's millivolts, and tests it against
        250 as the driver does (modev3devices.c TouchSensor_pressed).  The simulated sensor's bin_data
        holds value0 itself, 0 or 1 (docs/fidelity.md, lego-ev3-touch-bin-data), so the test here is
        above 0, which gives the same answer for either."""
        return _sensor.value(self._record, "TOUCH") > 0


class ColorSensor(_sensor.Sensor):
    """LEGO MINDSTORMS EV3 Color Sensor."""

    _DRIVERS = ("lego-ev3-color",)
    _SWITCH_DELAY_MS = 30  # pbdevice.c get_mode_switch_delay

    def reflection(self):
        """Reflected red light, 0 (no reflection) to 100 (high reflection): an int."""
        return _sensor.value(self._record, "COL-REFLECT")

    def ambient(self):
        """Ambient light, 0 (dark) to 100 (bright): an int."""
        return _sensor.value(self._record, "COL-AMBIENT")

    def color(self):
        """The colour of the surface: Color.BLACK, BLUE, GREEN, YELLOW, RED, WHITE, BROWN, or None."""
        return _COLORS.get(_sensor.value(self._record, "COL-COLOR"))

    def rgb(self):
        """Reflected red, green and blue light, each 0 to 100: a tuple of ints (the firmware's scaling of
        RGB-RAW: 0.258 r - 0.3, 0.280 g - 0.8, 0.523 b - 3.7, truncated and kept within 0-100)."""
        r, g, b = _sensor.values(self._record, "RGB-RAW")[:3]
        return (_percent(0.258 * r - 0.3), _percent(0.280 * g - 0.8), _percent(0.523 * b - 3.7))


def _percent(scaled):
    value = int(scaled)
    return 100 if value > 100 else 0 if value < 0 else value


class InfraredSensor(_sensor.Sensor):
    """LEGO MINDSTORMS EV3 Infrared Sensor and Beacon."""

    _DRIVERS = ("lego-ev3-ir",)
    _SWITCH_DELAY_MS = 1100  # pbdevice.c get_mode_switch_delay

    def distance(self):
        """Relative distance to the nearest object, 0 (closest) to 100 (farthest): an int."""
        return _sensor.value(self._record, "IR-PROX")

    def beacon(self, channel):
        """(distance 0-100, heading in degrees) of the remote's beacon on `channel` (1-4), or (None, None)
        when no beacon is seen."""
        number = _channel(channel)
        data = _sensor.values(self._record, "IR-SEEK")
        heading, distance = data[number * 2 - 2] * 3, data[number * 2 - 1]
        if distance == -128:
            return (None, None)
        return (distance, heading)

    def buttons(self, channel):
        """The buttons pressed on the remote on `channel` (1-4): a list of at most two Buttons."""
        number = _channel(channel)
        code = _sensor.values(self._record, "IR-REMOTE")[number - 1]
        pressed = _REMOTE.get(code)
        if pressed is None:  # pb_assert(PBIO_ERROR_IO)
            raise OSError(5, "EIO: the infrared sensor sent an unknown remote code")
        return list(pressed)

    def keypad(self):
        """The up/down buttons pressed on the remote on channel 1: a list of Buttons (not the beacon)."""
        data = _sensor.value(self._record, "IR-REM-A")
        if data == 384:
            return []
        return [button for bit, button in _KEYPAD if data & bit]


class UltrasonicSensor(_sensor.Sensor):
    """LEGO MINDSTORMS EV3 Ultrasonic Sensor."""

    _DRIVERS = ("lego-ev3-us",)

    def distance(self, silent=False):
        """Distance to the nearest object in mm (an int).  silent=True takes a single measurement (US-SI-CM,
        the mode written again on every call) and leaves the sensor quiet."""
        if silent:  # pbdevice.c get_values writes a single-measurement mode even when it is set already
            _sensor.switch(self._record, "US-SI-CM")
            return _sensor.value(self._record, "US-SI-CM")
        return _sensor.value(self._record, "US-DIST-CM")

    def presence(self):
        """True if the sensor hears another ultrasonic sensor."""
        return bool(_sensor.value(self._record, "US-LISTEN"))


class GyroSensor(_sensor.Sensor):
    """LEGO MINDSTORMS EV3 Gyro Sensor: angle and speed, clockwise positive unless direction says else.

    The firmware's keyword is `direction` (modev3devices.c ev3devices_GyroSensor_make_new; the
    documentation's `positive_direction` is refused by the firmware, and so here)."""

    _DRIVERS = ("lego-ev3-gyro",)

    def __init__(self, port, direction=Direction.CLOCKWISE):
        if direction is not Direction.CLOCKWISE and direction is not Direction.COUNTERCLOCKWISE:
            raise TypeError("direction must be Direction.CLOCKWISE or Direction.COUNTERCLOCKWISE")
        super().__init__(port)
        self._clockwise = direction is Direction.CLOCKWISE
        self._offset = self._angle_offset(0)

    def _angle_offset(self, new_angle):
        """ev3devices_GyroSensor_get_angle_offset: the offset that makes angle() read new_angle now."""
        raw = _sensor.value(self._record, "GYRO-ANG")
        return raw - new_angle if self._clockwise else -raw - new_angle

    def speed(self):
        """Rotational speed in deg/s.  It reads GYRO-RATE; switching to it resets the sensor's angle, so the
        firmware sets its offset to 0 (the next angle() counts from here)."""
        raw = _sensor.value(self._record, "GYRO-RATE")
        self._offset = 0
        return raw if self._clockwise else -raw

    def angle(self):
        """Accumulated angle in degrees."""
        raw = _sensor.value(self._record, "GYRO-ANG")
        return raw - self._offset if self._clockwise else -raw - self._offset

    def reset_angle(self, angle):
        """Make angle() read `angle` now."""
        self._offset = self._angle_offset(get_int(angle))
