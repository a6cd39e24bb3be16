"""The brick's status LEDs (python-ev3dev2 2.1.0), through the sysfs class 'leds'."""

import _thread
import os  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import stat  # noqa: F401
import sys  # noqa: F401
import time
from collections import OrderedDict
from time import sleep  # noqa: F401  (only for star imports; the shim calls time.sleep, which a run replaces)

from ev3dev2 import Device, _attribute, get_current_platform
from ev3dev2._platform.ev3 import LED_COLORS, LED_DEFAULT_COLOR, LED_GROUPS, LEDS
from ev3dev2.stopwatch import StopWatch

platform = get_current_platform()
if platform == "fake":
    from ev3dev2._platform.fake import LED_COLORS, LED_DEFAULT_COLOR, LED_GROUPS, LEDS


class Led(Device):
    """One LED of the generic LED driver (see the kernel's leds-class.txt)."""

    SYSTEM_CLASS_NAME = "leds"
    SYSTEM_DEVICE_NAME_CONVENTION = "*"
    __slots__ = [
        "_max_brightness",
        "_brightness",
        "_triggers",
        "_trigger",
        "_delay_on",
        "_delay_off",
        "desc",
    ]

    def __init__(self, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, desc=None, **kwargs):
        self.desc = desc
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)
        self._max_brightness = None
        self._brightness = None
        self._triggers = None
        self._trigger = None
        self._delay_on = None
        self._delay_off = None

    def __str__(self):
        if self.desc:
            return self.desc
        else:
            return Device.__str__(self)

    max_brightness = _attribute(
        "max_brightness", "The largest brightness value.", writable=False, cached=True
    )
    brightness = _attribute("brightness", "The brightness, 0 to ``max_brightness``.")
    triggers = _attribute("trigger", "The available triggers.", kind="set", writable=False)

    @property
    def trigger(self):
        """
        The LED's trigger, a kernel source of LED events; e.g. ``timer``
        blinks it, with ``delay_on`` and ``delay_off`` milliseconds.
        """
        # Upstream unpacks get_attr_from_set()'s single string into two
        # names, which fails; this returns the selected trigger instead.
        self._trigger, value = self.get_attr_line(self._trigger, "trigger")
        for name in value.split():
            if name.strip("[]") != name:
                return name.strip("[]")
        return ""

    @trigger.setter
    def trigger(self, value):
        # Upstream then waits for the delay_on/delay_off files of the 'timer'
        # trigger to appear; the simulated brick has them at once.
        self._trigger = self.set_attr_string(self._trigger, "trigger", value)

    @property
    def delay_on(self):
        """Milliseconds on in each blink of the ``timer`` trigger."""
        for retry in (True, False):
            try:
                self._delay_on, value = self.get_attr_int(self._delay_on, "delay_on")
                return value
            except OSError:
                if retry:
                    self._delay_on = None
                else:
                    raise

    @delay_on.setter
    def delay_on(self, value):
        for retry in (True, False):
            try:
                self._delay_on = self.set_attr_int(self._delay_on, "delay_on", value)
                return
            except OSError:
                if retry:
                    self._delay_on = None
                else:
                    raise

    @property
    def delay_off(self):
        """Milliseconds off in each blink of the ``timer`` trigger."""
        for retry in (True, False):
            try:
                self._delay_off, value = self.get_attr_int(self._delay_off, "delay_off")
                return value
            except OSError:
                if retry:
                    self._delay_off = None
                else:
                    raise

    @delay_off.setter
    def delay_off(self, value):
        for retry in (True, False):
            try:
                self._delay_off = self.set_attr_int(self._delay_off, "delay_off", value)
                return
            except OSError:
                if retry:
                    self._delay_off = None
                else:
                    raise

    @property
    def brightness_pct(self):
        """The brightness as a fraction (0 to 1) of max_brightness."""
        return float(self.brightness) / self.max_brightness

    @brightness_pct.setter
    def brightness_pct(self, value):
        self.brightness = value * self.max_brightness


def _wait_while(condition):
    """Spin until ``condition()`` is false; sleep(0) lets other (simulated) threads run."""
    while condition():
        time.sleep(0)


class Leds:
    """The brick's LEDs, in groups ('LEFT', 'RIGHT') set to named colours."""

    def __init__(self):
        self.leds = OrderedDict()
        self.led_groups = OrderedDict()
        self.led_colors = LED_COLORS
        self.animate_thread_id = None
        self.animate_thread_stop = False

        for key, value in LEDS.items():
            self.leds[key] = Led(name_pattern=value, desc=key)

        for key, value in LED_GROUPS.items():
            self.led_groups[key] = []

            for led_name in value:
                self.led_groups[key].append(self.leds[led_name])

    def __str__(self):
        return self.__class__.__name__

    def set_color(self, group, color, pct=1):
        """
        Set the LEDs of ``group`` to ``color``, a name from LED_COLORS or a
        tuple of brightnesses (0 to 1), scaled by ``pct``.

        Example: ``Leds().set_color('LEFT', 'AMBER')`` or ``set_color('LEFT', (0.5, 0.3))``.
        """
        # If this is a platform without LEDs there is nothing to do
        if not self.leds:
            return

        color_tuple = color
        if isinstance(color, str):
            assert color in self.led_colors, "{} is an invalid LED color, valid choices are {}".format(
                color, ", ".join(self.led_colors.keys())
            )
            color_tuple = self.led_colors[color]

        assert group in self.led_groups, "{} is an invalid LED group, valid choices are {}".format(
            group, ", ".join(self.led_groups.keys())
        )

        for led, value in zip(self.led_groups[group], color_tuple, strict=False):
            led.brightness_pct = value * pct

    def set(self, group, **kwargs):
        """
        Set attributes of each LED in ``group``, e.g.
        ``Leds().set('LEFT', brightness_pct=0.5, trigger='timer')``.
        """
        # If this is a platform without LEDs there is nothing to do
        if not self.leds:
            return

        assert group in self.led_groups, "{} is an invalid LED group, valid choices are {}".format(
            group, ", ".join(self.led_groups.keys())
        )

        for led in self.led_groups[group]:
            for k in kwargs:
                setattr(led, k, kwargs[k])

    def all_off(self):
        """Turn all LEDs off."""
        # If this is a platform without LEDs there is nothing to do
        if not self.leds:
            return

        self.animate_stop()
        self._all_leds_off()

    def _all_leds_off(self):
        # Upstream's animations call all_off() from inside the animation
        # thread, whose animate_stop() then waits for that very thread; the
        # animations here switch the LEDs off directly (the same writes).
        for led in self.leds.values():
            led.brightness = 0

    def reset(self):
        """Put all LEDs back to their default colour."""
        if not self.leds:
            return

        self.animate_stop()

        for group in self.led_groups:
            self.set_color(group, LED_DEFAULT_COLOR)

    def animate_stop(self):
        """Signal the current animation thread to exit and wait for it to exit."""
        if self.animate_thread_id:
            self.animate_thread_stop = True
            _wait_while(lambda: self.animate_thread_id)

    def _animate(self, step, sleeptime, duration, block, before=None):
        """Run ``step()`` every ``sleeptime`` s for ``duration`` s (None: forever), here or in a thread."""

        def _run():
            if before is not None:
                before()
            duration_ms = duration * 1000 if duration is not None else None
            stopwatch = StopWatch()
            stopwatch.start()

            while True:
                step()

                if self.animate_thread_stop or stopwatch.is_elapsed_ms(duration_ms):
                    break

                time.sleep(sleeptime)

            self.animate_thread_stop = False
            self.animate_thread_id = None

        self.animate_stop()

        if block:
            _run()
        else:
            self.animate_thread_id = _thread.start_new_thread(_run, ())

    def animate_police_lights(
        self, color1, color2, group1="LEFT", group2="RIGHT", sleeptime=0.5, duration=5, block=True
    ):
        """
        Alternate ``group1`` and ``group2`` between ``color1`` and ``color2``
        every ``sleeptime`` seconds, for ``duration`` seconds (None: forever).

        Example: ``Leds().animate_police_lights('RED', 'GREEN', sleeptime=0.75, duration=10)``
        """
        even = [True]

        def step():
            if even[0]:
                self.set_color(group1, color1)
                self.set_color(group2, color2)
            else:
                self.set_color(group1, color2)
                self.set_color(group2, color1)
            even[0] = not even[0]

        self._animate(step, sleeptime, duration, block, before=self._all_leds_off)

    def animate_flash(self, color, groups=("LEFT", "RIGHT"), sleeptime=0.5, duration=5, block=True):
        """
        Turn the LEDs of ``groups`` on (``color``) and off every ``sleeptime``
        seconds, for ``duration`` seconds (None: forever).
        """
        even = [True]

        def step():
            if even[0]:
                for group in groups:
                    self.set_color(group, color)
            else:
                self._all_leds_off()
            even[0] = not even[0]

        self._animate(step, sleeptime, duration, block)

    def animate_cycle(self, colors, groups=("LEFT", "RIGHT"), sleeptime=0.5, duration=5, block=True):
        """
        Show each of ``colors`` in turn on ``groups`` for ``sleeptime`` seconds,
        for ``duration`` seconds (None: forever).
        """
        index = [0]

        def step():
            for group in groups:
                self.set_color(group, colors[index[0]])
            index[0] = (index[0] + 1) % len(colors)

        self._animate(step, sleeptime, duration, block)

    def animate_rainbow(
        self, group1="LEFT", group2="RIGHT", increment_by=0.1, sleeptime=0.1, duration=5, block=True
    ):
        """
        Fade gradually through red, amber, green and off, for ``duration``
        seconds (None: forever).
        """
        # state 0: (LEFT,RIGHT) from (0,0) to (1,0)...RED
        # state 1: (LEFT,RIGHT) from (1,0) to (1,1)...AMBER
        # state 2: (LEFT,RIGHT) from (1,1) to (0,1)...GREEN
        # state 3: (LEFT,RIGHT) from (0,1) to (0,0)...OFF
        MIN_VALUE = 0
        MAX_VALUE = 1
        values = {"state": 0, "left": 0, "right": 0}

        def step():
            state = values["state"]
            if state == 0:
                values["left"] += increment_by
            elif state == 1:
                values["right"] += increment_by
            elif state == 2:
                values["left"] -= increment_by
            elif state == 3:
                values["right"] -= increment_by
            else:
                raise Exception(f"Invalid state {state}")

            # Keep left and right within the MIN/MAX values
            left_value = values["left"] = max(min(values["left"], MAX_VALUE), MIN_VALUE)
            right_value = values["right"] = max(min(values["right"], MAX_VALUE), MIN_VALUE)

            self.set_color(group1, (left_value, right_value))
            self.set_color(group2, (left_value, right_value))

            if state == 0 and left_value == MAX_VALUE:
                values["state"] = 1
            elif state == 1 and right_value == MAX_VALUE:
                values["state"] = 2
            elif state == 2 and left_value == MIN_VALUE:
                values["state"] = 3
            elif state == 3 and right_value == MIN_VALUE:
                values["state"] = 0

        self._animate(step, sleeptime, duration, block, before=self._all_leds_off)
