"""
The EV3 brick's buttons (python-ev3dev2 2.1.0).

The simulator reports the pressed buttons through ``_link.call('buttons')``,
which returns a list of names out of up, down, left, right, enter, backspace
(a read costs the brick about 1 ms, as on an EV3).

The waits react to button *events*, as python-ev3dev2 2.1.0's do: there they read
the buttons' input events (evdev's ``read_loop``) and look at the buttons at each
one, so a button already down when a wait starts ends nothing, a new press does.
Here the buttons are looked at every 10 ms (of virtual time inside a run), and a
change since the last look is an event.  ``process()`` compares with its last
call, as upstream's does (its first call compares with no button pressed).
Unlike upstream's, a wait's ``timeout_ms`` ends it even when no button moves.
"""

import array  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import sys  # noqa: F401
import time
from logging import getLogger

from ev3dev2 import _link, get_current_platform, is_micropython, library_load_warning_message  # noqa: F401
from ev3dev2.stopwatch import StopWatch

try:
    import fcntl  # noqa: F401
except ImportError:
    pass

platform = get_current_platform()

# the platform's button file names, as upstream imports them (the simulated brick is an EV3; 'fake' with
# FAKE_SYS set, as python-ev3dev2's own tests run)
if platform == "fake":
    from ev3dev2._platform.fake import BUTTONS_FILENAME, EVDEV_DEVICE_NAME  # noqa: F401
else:
    from ev3dev2._platform.ev3 import BUTTONS_FILENAME, EVDEV_DEVICE_NAME  # noqa: F401

log = getLogger(__name__)

# How often the wait_for_* methods look at the buttons, in seconds.
_POLL_INTERVAL = 0.01


class MissingButton(Exception):
    pass


class ButtonCommon:
    def __str__(self):
        return self.__class__.__name__

    @staticmethod
    def on_change(changed_buttons):
        """
        Called by ``process()`` whenever any button changed since the last
        call, with a list of (button name, pressed) tuples.
        """
        pass

    @property
    def buttons_pressed(self):
        raise NotImplementedError()

    def any(self):
        """True if any button is pressed."""
        return bool(self.buttons_pressed)

    def check_buttons(self, buttons=[]):  # noqa: B006 - upstream's signature
        """True if exactly the buttons ``buttons`` are pressed."""
        return set(self.buttons_pressed) == set(buttons)

    def _wait(self, wait_for_button_press, wait_for_button_release, timeout_ms):
        raise NotImplementedError()

    def wait_for_pressed(self, buttons, timeout_ms=None):
        """Wait for ``buttons`` (a name or a list) to be pressed; False on timeout."""
        return self._wait(buttons, [], timeout_ms)

    def wait_for_released(self, buttons, timeout_ms=None):
        """Wait for ``buttons`` (a name or a list) to be released; False on timeout."""
        return self._wait([], buttons, timeout_ms)

    def wait_for_bump(self, buttons, timeout_ms=None):
        """
        Wait for ``buttons`` to be pressed down and then released, both
        within ``timeout_ms``.
        """
        stopwatch = StopWatch()
        stopwatch.start()

        if self.wait_for_pressed(buttons, timeout_ms):
            if timeout_ms is not None:
                timeout_ms -= stopwatch.value_ms
            return self.wait_for_released(buttons, timeout_ms)

        return False

    def process(self, new_state=None):
        """
        Check the pressed buttons; for each one that changed since the last
        call, call its handler (``on_up``, ``on_enter``, ...) with its new
        state, then ``on_change`` with all the changes.
        """
        if new_state is None:
            new_state = set(self.buttons_pressed)
        old_state = self._state if hasattr(self, "_state") else set()
        self._state = new_state

        state_diff = new_state.symmetric_difference(old_state)
        for button in state_diff:
            handler = getattr(self, "on_" + button)

            if handler is not None:
                handler(button in new_state)

        if self.on_change is not None and state_diff:
            self.on_change([(button, button in new_state) for button in state_diff])


class EV3ButtonCommon:
    # Handlers called by ButtonCommon.process() when a button's state changes.
    on_up = None
    on_down = None
    on_left = None
    on_right = None
    on_enter = None
    on_backspace = None

    @property
    def up(self):
        """True if the ``up`` button is pressed."""
        return "up" in self.buttons_pressed

    @property
    def down(self):
        """True if the ``down`` button is pressed."""
        return "down" in self.buttons_pressed

    @property
    def left(self):
        """True if the ``left`` button is pressed."""
        return "left" in self.buttons_pressed

    @property
    def right(self):
        """True if the ``right`` button is pressed."""
        return "right" in self.buttons_pressed

    @property
    def enter(self):
        """True if the ``enter`` button is pressed."""
        return "enter" in self.buttons_pressed

    @property
    def backspace(self):
        """True if the ``backspace`` button is pressed."""
        return "backspace" in self.buttons_pressed


class ButtonBase(ButtonCommon):
    """Abstract button interface."""

    _state = set([])

    @property
    def evdev_device(self):
        """The Linux input device; there is none in the simulator."""
        raise Exception(
            "{}: could not find evdev device '{}'".format(self, getattr(self, "evdev_device_name", None))
        )

    def process_forever(self):
        """Call ``process()`` whenever the buttons may have changed, forever."""
        while True:
            self.process()
            time.sleep(_POLL_INTERVAL)


class ButtonEVIO(ButtonBase):
    """Buttons read from the simulated brick (on a real EV3: the Linux event interface)."""

    KEY_MAX = 0x2FF
    KEY_BUF_LEN = int((KEY_MAX + 7) / 8)
    EVIOCGKEY = 2 << (14 + 8 + 8) | KEY_BUF_LEN << (8 + 8) | ord("E") << 8 | 0x18

    _buttons = {}

    def __init__(self):
        super().__init__()
        if not _link.connected():
            raise _link.NotInSimulation(_link.OUTSIDE_MESSAGE)

        for b in self._buttons:
            if self._buttons[b]["name"] is None:
                raise MissingButton(f"Button '{b}' is not available on this platform")

    @property
    def buttons_pressed(self):
        """The names of the pressed buttons."""
        pressed = set(_link.call("buttons") or ())
        return [name for name in self._buttons if name in pressed]

    def _wait(self, wait_for_button_press, wait_for_button_release, timeout_ms):
        stopwatch = StopWatch()
        stopwatch.start()

        # A single button may be given by its name.
        if isinstance(wait_for_button_press, str):
            wait_for_button_press = [wait_for_button_press]

        if isinstance(wait_for_button_release, str):
            wait_for_button_release = [wait_for_button_release]

        before = set(self.buttons_pressed)  # a button down already is no event
        while True:
            if timeout_ms is not None and stopwatch.value_ms >= timeout_ms:
                return False

            if timeout_ms is None:
                _link.call("buttons", "wait")  # the simulator stops a wait that no scripted press can end

            time.sleep(_POLL_INTERVAL)
            pressed = set(self.buttons_pressed)
            if pressed == before:
                continue
            before = pressed  # an event: a button went down or up

            all_pressed = all(button in pressed for button in wait_for_button_press)
            all_released = not any(button in pressed for button in wait_for_button_release)

            if all_pressed and all_released:
                return True


class Button(ButtonEVIO, EV3ButtonCommon):
    """The six buttons of the EV3 brick."""

    _buttons = {
        "up": {"name": BUTTONS_FILENAME, "value": 103},
        "down": {"name": BUTTONS_FILENAME, "value": 108},
        "left": {"name": BUTTONS_FILENAME, "value": 105},
        "right": {"name": BUTTONS_FILENAME, "value": 106},
        "enter": {"name": BUTTONS_FILENAME, "value": 28},
        "backspace": {"name": BUTTONS_FILENAME, "value": 14},
    }
    evdev_device_name = EVDEV_DEVICE_NAME
