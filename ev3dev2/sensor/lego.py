"""The LEGO sensors (python-ev3dev2 2.1.0): touch, colour, ultrasonic, gyro, infrared, NXT sound and light."""

import logging
import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import time

from ev3dev2.button import ButtonBase
from ev3dev2.sensor import Sensor

log = logging.getLogger(__name__)


class TouchSensor(Sensor):
    """Touch Sensor"""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Button state
    MODE_TOUCH = "TOUCH"
    MODES = (MODE_TOUCH,)

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(
            address, name_pattern, name_exact, driver_name=["lego-ev3-touch", "lego-nxt-touch"], **kwargs
        )

    @property
    def is_pressed(self):
        """Whether the sensor is pressed (1) or not (0)."""
        self._ensure_mode(self.MODE_TOUCH)
        return self.value(0)

    @property
    def is_released(self):
        return not self.is_pressed

    def _wait(self, wait_for_press, timeout_ms, sleep_ms):
        tic = time.time()

        if sleep_ms:
            sleep_ms = float(sleep_ms / 1000)

        # The sensor cannot be polled for changes, so check often
        while True:
            if self.is_pressed == wait_for_press:
                return True

            if timeout_ms is not None and time.time() >= tic + timeout_ms / 1000:
                return False

            if sleep_ms:
                time.sleep(sleep_ms)

    def wait_for_pressed(self, timeout_ms=None, sleep_ms=10):
        """Wait for the touch sensor to be pressed down; False on timeout."""
        return self._wait(True, timeout_ms, sleep_ms)

    def wait_for_released(self, timeout_ms=None, sleep_ms=10):
        """Wait for the touch sensor to be released; False on timeout."""
        return self._wait(False, timeout_ms, sleep_ms)

    def wait_for_bump(self, timeout_ms=None, sleep_ms=10):
        """Wait for the touch sensor to be pressed and released, both within ``timeout_ms``."""
        start_time = time.time()

        if self.wait_for_pressed(timeout_ms, sleep_ms):
            if timeout_ms is not None:
                timeout_ms -= int((time.time() - start_time) * 1000)
            return self.wait_for_released(timeout_ms, sleep_ms)

        return False


class ColorSensor(Sensor):
    """LEGO EV3 color sensor."""

    __slots__ = ["red_max", "green_max", "blue_max"]

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Reflected light. Red LED on.
    MODE_COL_REFLECT = "COL-REFLECT"

    #: Ambient light. Blue LEDs on.
    MODE_COL_AMBIENT = "COL-AMBIENT"

    #: Color. All LEDs rapidly cycling, appears white.
    MODE_COL_COLOR = "COL-COLOR"

    #: Raw reflected. Red LED on
    MODE_REF_RAW = "REF-RAW"

    #: Raw Color Components. All LEDs rapidly cycling, appears white.
    MODE_RGB_RAW = "RGB-RAW"

    #: No color.
    COLOR_NOCOLOR = 0

    #: Black color.
    COLOR_BLACK = 1

    #: Blue color.
    COLOR_BLUE = 2

    #: Green color.
    COLOR_GREEN = 3

    #: Yellow color.
    COLOR_YELLOW = 4

    #: Red color.
    COLOR_RED = 5

    #: White color.
    COLOR_WHITE = 6

    #: Brown color.
    COLOR_BROWN = 7

    MODES = (MODE_COL_REFLECT, MODE_COL_AMBIENT, MODE_COL_COLOR, MODE_REF_RAW, MODE_RGB_RAW)

    COLORS = (
        "NoColor",
        "Black",
        "Blue",
        "Green",
        "Yellow",
        "Red",
        "White",
        "Brown",
    )

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name="lego-ev3-color", **kwargs)

        # See calibrate_white() for more details
        self.red_max = 300
        self.green_max = 300
        self.blue_max = 300

    @property
    def reflected_light_intensity(self):
        """Reflected light intensity as a percentage (0 to 100); the sensor's light is red."""
        self._ensure_mode(self.MODE_COL_REFLECT)
        return self.value(0)

    @property
    def ambient_light_intensity(self):
        """Ambient light intensity as a percentage (0 to 100); the sensor's light is dim blue."""
        self._ensure_mode(self.MODE_COL_AMBIENT)
        return self.value(0)

    @property
    def color(self):
        """
        The colour detected: 0 no color, 1 black, 2 blue, 3 green, 4 yellow,
        5 red, 6 white, 7 brown.
        """
        self._ensure_mode(self.MODE_COL_COLOR)
        return self.value(0)

    @property
    def color_name(self):
        """The colour detected by name: NoColor, Black, Blue, etc."""
        return self.COLORS[self.color]

    @property
    def raw(self):
        """
        Red, green and blue components of the detected colour, as a tuple
        (officially 0-1020; white paper reads about 250-400).  See rgb() and
        calibrate_white().
        """
        self._ensure_mode(self.MODE_RGB_RAW)
        return self.value(0), self.value(1), self.value(2)

    def calibrate_white(self):
        """
        Call this over a white surface: its raw readings become the maxima
        (default 300 each) that rgb() scales to 255.
        """
        (self.red_max, self.green_max, self.blue_max) = self.raw

    @property
    def rgb(self):
        """Same as raw, but scaled to 0-255 using the calibrate_white() maxima."""
        (red, green, blue) = self.raw

        return (
            min(int((red * 255) / self.red_max), 255),
            min(int((green * 255) / self.green_max), 255),
            min(int((blue * 255) / self.blue_max), 255),
        )

    @property
    def lab(self):
        """The colour in the Lab colour space."""
        RGB = [0, 0, 0]
        XYZ = [0, 0, 0]

        for num, value in enumerate(self.rgb):
            if value > 0.04045:
                value = pow(((value + 0.055) / 1.055), 2.4)
            else:
                value = value / 12.92

            RGB[num] = value * 100.0

        # sRGB to XYZ, http://www.brucelindbloom.com/index.html?Eqn_RGB_XYZ_Matrix.html
        X = (RGB[0] * 0.4124564) + (RGB[1] * 0.3575761) + (RGB[2] * 0.1804375)
        Y = (RGB[0] * 0.2126729) + (RGB[1] * 0.7151522) + (RGB[2] * 0.0721750)
        Z = (RGB[0] * 0.0193339) + (RGB[1] * 0.1191920) + (RGB[2] * 0.9503041)

        XYZ[0] = X / 95.047  # ref_X =  95.047
        XYZ[1] = Y / 100.0  # ref_Y = 100.000
        XYZ[2] = Z / 108.883  # ref_Z = 108.883

        for num, value in enumerate(XYZ):
            if value > 0.008856:
                value = pow(value, (1.0 / 3.0))
            else:
                value = (7.787 * value) + (16 / 116.0)

            XYZ[num] = value

        L = (116.0 * XYZ[1]) - 16
        a = 500.0 * (XYZ[0] - XYZ[1])
        b = 200.0 * (XYZ[1] - XYZ[2])

        L = round(L, 4)
        a = round(a, 4)
        b = round(b, 4)

        return (L, a, b)

    @property
    def hsv(self):
        """The colour as (hue 0-1, saturation 0-1, value 0-255)."""
        (r, g, b) = self.rgb
        maxc = max(r, g, b)
        minc = min(r, g, b)
        v = maxc

        if minc == maxc:
            return 0.0, 0.0, v

        s = (maxc - minc) / maxc
        rc = (maxc - r) / (maxc - minc)
        gc = (maxc - g) / (maxc - minc)
        bc = (maxc - b) / (maxc - minc)

        if r == maxc:
            h = bc - gc
        elif g == maxc:
            h = 2.0 + rc - bc
        else:
            h = 4.0 + gc - rc

        h = (h / 6.0) % 1.0

        return (h, s, v)

    @property
    def hls(self):
        """The colour as (hue, lightness, saturation), computed as upstream does from rgb."""
        (red, green, blue) = self.rgb
        maxc = max(red, green, blue)
        minc = min(red, green, blue)
        luminance = (minc + maxc) / 2.0

        if minc == maxc:
            return 0.0, luminance, 0.0

        if luminance <= 0.5:
            saturation = (maxc - minc) / (maxc + minc)
        else:
            if 2.0 - maxc - minc == 0:
                saturation = 0
            else:
                saturation = (maxc - minc) / (2.0 - maxc - minc)

        rc = (maxc - red) / (maxc - minc)
        gc = (maxc - green) / (maxc - minc)
        bc = (maxc - blue) / (maxc - minc)

        if red == maxc:
            hue = bc - gc
        elif green == maxc:
            hue = 2.0 + rc - bc
        else:
            hue = 4.0 + gc - rc

        hue = (hue / 6.0) % 1.0

        return (hue, luminance, saturation)

    @property
    def red(self):
        """Red component of the detected colour, 0-1020."""
        self._ensure_mode(self.MODE_RGB_RAW)
        return self.value(0)

    @property
    def green(self):
        """Green component of the detected colour, 0-1020."""
        self._ensure_mode(self.MODE_RGB_RAW)
        return self.value(1)

    @property
    def blue(self):
        """Blue component of the detected colour, 0-1020."""
        self._ensure_mode(self.MODE_RGB_RAW)
        return self.value(2)


class UltrasonicSensor(Sensor):
    """LEGO EV3 ultrasonic sensor."""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Continuous measurement in centimeters.
    MODE_US_DIST_CM = "US-DIST-CM"

    #: Continuous measurement in inches.
    MODE_US_DIST_IN = "US-DIST-IN"

    #: Listen.
    MODE_US_LISTEN = "US-LISTEN"

    #: Single measurement in centimeters.
    MODE_US_SI_CM = "US-SI-CM"

    #: Single measurement in inches.
    MODE_US_SI_IN = "US-SI-IN"

    MODES = (
        MODE_US_DIST_CM,
        MODE_US_DIST_IN,
        MODE_US_LISTEN,
        MODE_US_SI_CM,
        MODE_US_SI_IN,
    )

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(
            address, name_pattern, name_exact, driver_name=["lego-ev3-us", "lego-nxt-us"], **kwargs
        )

    @property
    def distance_centimeters_continuous(self):
        """Distance to the nearest object in cm, measured continuously (prefer ``distance_centimeters``)."""
        self._ensure_mode(self.MODE_US_DIST_CM)
        return self.value(0) * self._scale("US_DIST_CM")

    @property
    def distance_centimeters_ping(self):
        """
        Distance in cm from a single ping.  Pinging more often than every
        250 ms can lock up a real sensor.
        """
        # Setting this mode sends a ping; the mode itself does not change.
        self.mode = self.MODE_US_SI_CM
        return self.value(0) * self._scale("US_DIST_CM")

    @property
    def distance_centimeters(self):
        """Distance to the nearest object in cm (same as ``distance_centimeters_continuous``)."""
        return self.distance_centimeters_continuous

    @property
    def distance_inches_continuous(self):
        """Distance to the nearest object in inches, measured continuously (prefer ``distance_inches``)."""
        self._ensure_mode(self.MODE_US_DIST_IN)
        return self.value(0) * self._scale("US_DIST_IN")

    @property
    def distance_inches_ping(self):
        """
        Distance in inches from a single ping.  Pinging more often than every
        250 ms can lock up a real sensor.
        """
        # Setting this mode sends a ping; the mode itself does not change.
        self.mode = self.MODE_US_SI_IN
        return self.value(0) * self._scale("US_DIST_IN")

    @property
    def distance_inches(self):
        """Distance to the nearest object in inches (same as ``distance_inches_continuous``)."""
        return self.distance_inches_continuous

    @property
    def other_sensor_present(self):
        """Whether another ultrasonic sensor can be heard nearby."""
        self._ensure_mode(self.MODE_US_LISTEN)
        return bool(self.value(0))


class GyroSensor(Sensor):
    """LEGO EV3 gyro sensor."""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Angle
    MODE_GYRO_ANG = "GYRO-ANG"

    #: Rotational speed
    MODE_GYRO_RATE = "GYRO-RATE"

    #: Raw sensor value
    MODE_GYRO_FAS = "GYRO-FAS"

    #: Angle and rotational speed
    MODE_GYRO_G_A = "GYRO-G&A"

    #: Calibration
    MODE_GYRO_CAL = "GYRO-CAL"

    # Newer gyros also have a second axis, in the TILT-ANG and TILT-RATE
    # modes (not usable from the official EV3-G blocks)
    MODE_TILT_ANG = "TILT-ANG"
    MODE_TILT_RATE = "TILT-RATE"

    MODES = (
        MODE_GYRO_ANG,
        MODE_GYRO_RATE,
        MODE_GYRO_FAS,
        MODE_GYRO_G_A,
        MODE_GYRO_CAL,
        MODE_TILT_ANG,
        MODE_TILT_RATE,
    )

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name="lego-ev3-gyro", **kwargs)
        self._direct = None
        self._init_angle = self.angle

    @property
    def angle(self):
        """Degrees turned since the sensor was put in this mode (clockwise is positive)."""
        self._ensure_mode(self.MODE_GYRO_ANG)
        return self.value(0)

    @property
    def rate(self):
        """The rate of rotation, in degrees/second."""
        self._ensure_mode(self.MODE_GYRO_RATE)
        return self.value(0)

    @property
    def angle_and_rate(self):
        """Angle (degrees) and rate of rotation (degrees/second)."""
        self._ensure_mode(self.MODE_GYRO_G_A)
        return self.value(0), self.value(1)

    @property
    def tilt_angle(self):
        self._ensure_mode(self.MODE_TILT_ANG)
        return self.value(0)

    @property
    def tilt_rate(self):
        self._ensure_mode(self.MODE_TILT_RATE)
        return self.value(0)

    def calibrate(self):
        """Calibrate the gyro (takes 2 s); the robot must be perfectly still."""
        current_mode = self.mode
        self._ensure_mode(self.MODE_GYRO_CAL)
        time.sleep(2)
        self._ensure_mode(current_mode)

    def reset(self):
        """
        Resets the angle to 0 (this does not fix drift).
        """
        # 17 comes from inspecting the .vix file of the Gyro sensor block in EV3-G
        self._direct = self.set_attr_raw(self._direct, "direct", b"\x11")
        self._init_angle = self.angle

    def wait_until_angle_changed_by(self, delta, direction_sensitive=False):
        """
        Wait until the angle has changed by ``delta`` degrees (in the direction
        of its sign if ``direction_sensitive``, else either way).  The sensor
        must already be in an angle mode.
        """
        assert self.mode in (self.MODE_GYRO_G_A, self.MODE_GYRO_ANG, self.MODE_TILT_ANG), (
            "Gyro mode should be MODE_GYRO_ANG, MODE_GYRO_G_A or MODE_TILT_ANG"
        )
        start_angle = self.value(0)

        if direction_sensitive:
            if delta > 0:
                while (self.value(0) - start_angle) < delta:
                    time.sleep(0.01)
            else:
                delta *= -1
                while (start_angle - self.value(0)) < delta:
                    time.sleep(0.01)
        else:
            while abs(start_angle - self.value(0)) < delta:
                time.sleep(0.01)

    def circle_angle(self):
        """
        The heading as an angle on a circle (0-360, counter-clockwise
        positive), taking the gyro's starting position as 90 degrees.
        """
        current_angle = self.angle
        delta = abs(current_angle - self._init_angle) % 360

        if delta == 0:
            result = 90

        # the gyro has turned clockwise relative to where we started
        elif current_angle > self._init_angle:
            if delta <= 90:
                result = 90 - delta

            elif delta <= 180:
                result = 360 - (delta - 90)

            elif delta <= 270:
                result = 270 - (delta - 180)

            else:
                result = 180 - (delta - 270)

        # the gyro has turned counter-clockwise relative to where we started
        else:
            if delta <= 90:
                result = 90 + delta

            elif delta <= 180:
                result = 180 + (delta - 90)

            elif delta <= 270:
                result = 270 + (delta - 180)

            else:
                result = delta - 270

        return result


class InfraredSensor(Sensor, ButtonBase):
    """LEGO EV3 infrared sensor: proximity, beacon seeking and the IR remote's buttons."""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Proximity
    MODE_IR_PROX = "IR-PROX"

    #: IR Seeker
    MODE_IR_SEEK = "IR-SEEK"

    #: IR Remote Control
    MODE_IR_REMOTE = "IR-REMOTE"

    #: IR Remote Control. State of the buttons is coded in binary
    MODE_IR_REM_A = "IR-REM-A"

    #: Calibration
    MODE_IR_CAL = "IR-CAL"

    MODES = (MODE_IR_PROX, MODE_IR_SEEK, MODE_IR_REMOTE, MODE_IR_REM_A, MODE_IR_CAL)

    # The remote's button combinations, by the value the sensor reports.
    _BUTTON_VALUES = {
        0: [],
        1: ["top_left"],
        2: ["bottom_left"],
        3: ["top_right"],
        4: ["bottom_right"],
        5: ["top_left", "top_right"],
        6: ["top_left", "bottom_right"],
        7: ["bottom_left", "top_right"],
        8: ["bottom_left", "bottom_right"],
        9: ["beacon"],
        10: ["top_left", "bottom_left"],
        11: ["top_right", "bottom_right"],
    }

    _BUTTONS = ("top_left", "bottom_left", "top_right", "bottom_right", "beacon")

    # Button codes for doing rapid check of remote status
    NO_BUTTON = 0
    TOP_LEFT = 1
    BOTTOM_LEFT = 2
    TOP_RIGHT = 3
    BOTTOM_RIGHT = 4
    TOP_LEFT_TOP_RIGHT = 5
    TOP_LEFT_BOTTOM_RIGHT = 6
    BOTTOM_LEFT_TOP_RIGHT = 7
    BOTTOM_LEFT_BOTTOM_RIGHT = 8
    BEACON = 9
    TOP_LEFT_BOTTOM_LEFT = 10
    TOP_RIGHT_BOTTOM_RIGHT = 11

    #: Handlers for the remote's button events, per channel; see :meth:`InfraredSensor.process`.
    on_channel1_top_left = None
    on_channel1_bottom_left = None
    on_channel1_top_right = None
    on_channel1_bottom_right = None
    on_channel1_beacon = None

    on_channel2_top_left = None
    on_channel2_bottom_left = None
    on_channel2_top_right = None
    on_channel2_bottom_right = None
    on_channel2_beacon = None

    on_channel3_top_left = None
    on_channel3_bottom_left = None
    on_channel3_top_right = None
    on_channel3_bottom_right = None
    on_channel3_beacon = None

    on_channel4_top_left = None
    on_channel4_bottom_left = None
    on_channel4_top_right = None
    on_channel4_bottom_right = None
    on_channel4_beacon = None

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name="lego-ev3-ir", **kwargs)

    def _normalize_channel(self, channel):
        assert channel >= 1 and channel <= 4, f"channel is {channel}, it must be 1, 2, 3, or 4"
        channel = max(1, min(4, channel)) - 1
        return channel

    @property
    def proximity(self):
        """Distance to the nearest object as a percentage; 100% is about 70 cm."""
        self._ensure_mode(self.MODE_IR_PROX)
        return self.value(0)

    def heading(self, channel=1):
        """Heading (-25 to 25) to the beacon on ``channel``."""
        self._ensure_mode(self.MODE_IR_SEEK)
        channel = self._normalize_channel(channel)
        return self.value(channel * 2)

    def distance(self, channel=1):
        """Distance (0 to 100) to the beacon on ``channel``, or None when it is not found."""
        self._ensure_mode(self.MODE_IR_SEEK)
        channel = self._normalize_channel(channel)
        ret_value = self.value((channel * 2) + 1)

        # The value will be -128 if no beacon is found, return None instead
        return None if ret_value == -128 else ret_value

    def heading_and_distance(self, channel=1):
        """(heading, distance) to the beacon on ``channel``."""
        return (self.heading(channel), self.distance(channel))

    def top_left(self, channel=1):
        """Whether the remote's ``top_left`` button is pressed."""
        return "top_left" in self.buttons_pressed(channel)

    def bottom_left(self, channel=1):
        """Whether the remote's ``bottom_left`` button is pressed."""
        return "bottom_left" in self.buttons_pressed(channel)

    def top_right(self, channel=1):
        """Whether the remote's ``top_right`` button is pressed."""
        return "top_right" in self.buttons_pressed(channel)

    def bottom_right(self, channel=1):
        """Whether the remote's ``bottom_right`` button is pressed."""
        return "bottom_right" in self.buttons_pressed(channel)

    def beacon(self, channel=1):
        """Whether the remote's ``beacon`` button is on."""
        return "beacon" in self.buttons_pressed(channel)

    def buttons_pressed(self, channel=1):
        """The remote's pressed buttons on ``channel`` (at most two are recognised)."""
        self._ensure_mode(self.MODE_IR_REMOTE)
        channel = self._normalize_channel(channel)
        return self._BUTTON_VALUES.get(self.value(channel), [])

    def process(self):
        """
        Check the remote's buttons on all channels; for each change since the
        last call, call its handler (``on_channel1_top_left`` ...) with its new
        state, then ``on_change``.

        Example::

            ir.on_channel1_top_left = lambda state: print("top left:", state)
            while True:
                ir.process()
                time.sleep(0.01)
        """
        new_state = []
        state_diff = []

        for channel in range(1, 5):
            for button in self.buttons_pressed(channel):
                new_state.append((button, channel))

                # Key was not pressed before but now is pressed
                if (button, channel) not in self._state:
                    state_diff.append((button, channel))

            # Key was pressed but is no longer pressed
            for button in self._BUTTONS:
                if (button, channel) not in new_state and (button, channel) in self._state:
                    state_diff.append((button, channel))

        self._state = new_state

        for button, channel in state_diff:
            handler = getattr(self, "on_channel" + str(channel) + "_" + button)

            if handler is not None:
                handler((button, channel) in new_state)

        if self.on_change is not None and state_diff:
            # Upstream tests `button in new_state` (always False, as new_state
            # holds (button, channel) pairs); kept so programs behave the same.
            self.on_change([(button, channel, button in new_state) for (button, channel) in state_diff])


class SoundSensor(Sensor):
    """LEGO NXT Sound Sensor"""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Sound pressure level. Flat weighting
    MODE_DB = "DB"

    #: Sound pressure level. A weighting
    MODE_DBA = "DBA"

    MODES = (
        MODE_DB,
        MODE_DBA,
    )

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name="lego-nxt-sound", **kwargs)

    @property
    def sound_pressure(self):
        """Sound pressure level as a percent, flat weighting."""
        self._ensure_mode(self.MODE_DB)
        return self.value(0) * self._scale("DB")

    @property
    def sound_pressure_low(self):
        """Sound pressure level as a percent, A-weighting (levels up to 55 dB)."""
        self._ensure_mode(self.MODE_DBA)
        return self.value(0) * self._scale("DBA")


class LightSensor(Sensor):
    """LEGO NXT Light Sensor"""

    SYSTEM_CLASS_NAME = Sensor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = Sensor.SYSTEM_DEVICE_NAME_CONVENTION

    #: Reflected light. LED on
    MODE_REFLECT = "REFLECT"

    #: Ambient light. LED off
    MODE_AMBIENT = "AMBIENT"

    MODES = (
        MODE_REFLECT,
        MODE_AMBIENT,
    )

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name="lego-nxt-light", **kwargs)

    @property
    def reflected_light_intensity(self):
        """Reflected light intensity as a percentage."""
        self._ensure_mode(self.MODE_REFLECT)
        return self.value(0) * self._scale("REFLECT")

    @property
    def ambient_light_intensity(self):
        """Ambient light intensity as a percentage."""
        self._ensure_mode(self.MODE_AMBIENT)
        return self.value(0) * self._scale("AMBIENT")
