"""
Motors and motor pairs (python-ev3dev2 2.1.0): tacho, DC and servo motors,
speed units, and MoveTank / MoveSteering / MoveDifferential / MoveJoystick.

Every command is a sequence of attribute writes (``speed_sp``, ``position_sp``,
``stop_action``, ``command`` ...) in the same order, with the same rounding, as
the real library, so the simulated brick sees what a real one would.
"""

import _thread
import math
import select  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import sys  # noqa: F401
import time
from collections import OrderedDict
from logging import getLogger
from os.path import abspath  # noqa: F401

from ev3dev2 import (
    Device,
    DeviceNotDefined,
    ThreadNotRunning,
    _attribute,
    _link,
    get_current_platform,
    list_device_names,
)
from ev3dev2._platform.ev3 import OUTPUT_A, OUTPUT_B, OUTPUT_C, OUTPUT_D  # noqa: F401
from ev3dev2.stopwatch import StopWatch

platform = get_current_platform()
if platform == "fake":
    from ev3dev2._platform.fake import OUTPUT_A, OUTPUT_B, OUTPUT_C, OUTPUT_D  # noqa: F401

log = getLogger(__name__)

# The number of milliseconds we wait for the state of a motor to
# update to 'running' in the "on_for_XYZ" methods of the Motor class
WAIT_RUNNING_TIMEOUT = 100


class SpeedInvalid(ValueError):
    pass


class SpeedValue:
    """
    Base class of the speed units; use :class:`SpeedPercent`, :class:`SpeedNativeUnits`,
    :class:`SpeedRPS`, :class:`SpeedRPM`, :class:`SpeedDPS` or :class:`SpeedDPM`.
    """

    def __eq__(self, other):
        return self.to_native_units() == other.to_native_units()

    def __ne__(self, other):
        return not self.__eq__(other)

    def __lt__(self, other):
        return self.to_native_units() < other.to_native_units()

    def __le__(self, other):
        return self.to_native_units() <= other.to_native_units()

    def __gt__(self, other):
        return self.to_native_units() > other.to_native_units()

    def __ge__(self, other):
        return self.to_native_units() >= other.to_native_units()

    def __rmul__(self, other):
        return self.__mul__(other)


# In the __str__ methods below, upstream's expression parses as
# `"desc " if desc else ("" + value + unit)`: a speed with a description
# prints only the description.  Kept, since it shows in error messages.


class SpeedPercent(SpeedValue):
    """Speed as a percentage (-100 to 100) of the motor's maximum rated speed."""

    def __init__(self, percent, desc=None):
        if percent < -100 or percent > 100:
            raise SpeedInvalid(f"invalid percentage {percent}, must be between -100 and 100 (inclusive)")
        self.percent = percent
        self.desc = desc

    def __str__(self):
        return f"{self.desc} " if self.desc else "" + str(self.percent) + "%"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return SpeedPercent(self.percent * other)

    def to_native_units(self, motor):
        """This speed in the motor's native units (tacho counts per second)."""
        return self.percent / 100 * motor.max_speed


class SpeedNativeUnits(SpeedValue):
    """Speed in tacho counts per second."""

    def __init__(self, native_counts, desc=None):
        self.native_counts = native_counts
        self.desc = desc

    def __str__(self):
        return f"{self.desc} " if self.desc else "" + f"{self.native_counts:.2f}" + " counts/sec"

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return SpeedNativeUnits(self.native_counts * other)

    def to_native_units(self, motor=None):
        """This speed as a number (only speeds above max_speed are refused, as upstream)."""
        if self.native_counts > motor.max_speed:
            raise SpeedInvalid(
                f"invalid native-units: {motor} max speed {motor.max_speed}, {self.native_counts} was requested"
            )
        return self.native_counts


class _ScaledSpeed(SpeedValue):
    """A speed in a unit that scales to native units through the motor's max_rps/rpm/dps/dpm.

    Subclasses name the attribute that holds the number (as upstream's classes do),
    the motor's limit in that unit, and the words of upstream's messages.
    """

    _VALUE = _LIMIT = _NAME = _LIMIT_NAME = _SUFFIX = ""

    def __str__(self):
        return f"{self.desc} " if self.desc else "" + str(getattr(self, self._VALUE)) + self._SUFFIX

    def __mul__(self, other):
        assert isinstance(other, (float, int)), f"{self} can only be multiplied by an int or float"
        return type(self)(getattr(self, self._VALUE) * other)

    def to_native_units(self, motor):
        """The native speed (counts per second) that gives this speed on `motor`."""
        value, limit = getattr(self, self._VALUE), getattr(motor, self._LIMIT)
        if abs(value) > limit:
            raise SpeedInvalid(
                f"invalid {self._NAME}: {motor} max {self._LIMIT_NAME} is {limit}, {value} was requested"
            )
        return value / limit * motor.max_speed


class SpeedRPS(_ScaledSpeed):
    """Speed in rotations per second."""

    _VALUE, _LIMIT, _NAME, _LIMIT_NAME, _SUFFIX = (
        "rotations_per_second",
        "max_rps",
        "rotations-per-second",
        "RPS",
        " rot/sec",
    )

    def __init__(self, rotations_per_second, desc=None):
        self.rotations_per_second = rotations_per_second
        self.desc = desc


class SpeedRPM(_ScaledSpeed):
    """Speed in rotations per minute."""

    _VALUE, _LIMIT, _NAME, _LIMIT_NAME, _SUFFIX = (
        "rotations_per_minute",
        "max_rpm",
        "rotations-per-minute",
        "RPM",
        " rot/min",
    )

    def __init__(self, rotations_per_minute, desc=None):
        self.rotations_per_minute = rotations_per_minute
        self.desc = desc


class SpeedDPS(_ScaledSpeed):
    """Speed in degrees per second."""

    _VALUE, _LIMIT, _NAME, _LIMIT_NAME, _SUFFIX = (
        "degrees_per_second",
        "max_dps",
        "degrees-per-second",
        "DPS",
        " deg/sec",
    )

    def __init__(self, degrees_per_second, desc=None):
        self.degrees_per_second = degrees_per_second
        self.desc = desc


class SpeedDPM(_ScaledSpeed):
    """Speed in degrees per minute."""

    _VALUE, _LIMIT, _NAME, _LIMIT_NAME, _SUFFIX = (
        "degrees_per_minute",
        "max_dpm",
        "degrees-per-minute",
        "DPM",
        " deg/min",
    )

    def __init__(self, degrees_per_minute, desc=None):
        self.degrees_per_minute = degrees_per_minute
        self.desc = desc


def speed_to_speedvalue(speed, desc=None):
    """A ``SpeedValue`` as is; anything else is taken as a percentage."""
    if isinstance(speed, SpeedValue):
        return speed
    else:
        return SpeedPercent(speed, desc)


class Motor(Device):
    """
    A tacho motor: a motor with a rotary encoder, such as the EV3 and NXT
    motors, for precise control of speed and position.
    """

    SYSTEM_CLASS_NAME = "tacho-motor"
    SYSTEM_DEVICE_NAME_CONVENTION = "*"

    __slots__ = [
        "_address",
        "_command",
        "_commands",
        "_count_per_rot",
        "_count_per_m",
        "_driver_name",
        "_duty_cycle",
        "_duty_cycle_sp",
        "_full_travel_count",
        "_polarity",
        "_position",
        "_position_p",
        "_position_i",
        "_position_d",
        "_position_sp",
        "_max_speed",
        "_speed",
        "_speed_sp",
        "_ramp_up_sp",
        "_ramp_down_sp",
        "_speed_p",
        "_speed_i",
        "_speed_d",
        "_state",
        "_stop_action",
        "_stop_actions",
        "_time_sp",
        "_poll",
        "max_rps",
        "max_rpm",
        "max_dps",
        "max_dpm",
    ]

    #: Run the motor until another command is sent.
    COMMAND_RUN_FOREVER = "run-forever"

    #: Run to the absolute position ``position_sp``, then stop with ``stop_action``.
    COMMAND_RUN_TO_ABS_POS = "run-to-abs-pos"

    #: Run to ``position`` + ``position_sp``, then stop with ``stop_action``.
    COMMAND_RUN_TO_REL_POS = "run-to-rel-pos"

    #: Run for ``time_sp`` milliseconds, then stop with ``stop_action``.
    COMMAND_RUN_TIMED = "run-timed"

    #: Run at the duty cycle ``duty_cycle_sp``; changes to it take effect immediately.
    COMMAND_RUN_DIRECT = "run-direct"

    #: Stop any run command now, using ``stop_action``.
    COMMAND_STOP = "stop"

    #: Reset all motor attributes to their defaults (this also stops the motor).
    COMMAND_RESET = "reset"

    #: Sets the normal polarity of the rotary encoder.
    ENCODER_POLARITY_NORMAL = "normal"

    #: Sets the inversed polarity of the rotary encoder.
    ENCODER_POLARITY_INVERSED = "inversed"

    #: With ``normal`` polarity, a positive duty cycle turns the motor clockwise.
    POLARITY_NORMAL = "normal"

    #: With ``inversed`` polarity, a positive duty cycle turns the motor counter-clockwise.
    POLARITY_INVERSED = "inversed"

    #: Power is being sent to the motor.
    STATE_RUNNING = "running"

    #: The motor is ramping up or down and has not yet reached a constant output level.
    STATE_RAMPING = "ramping"

    #: The motor is not turning, but rather attempting to hold a fixed position.
    STATE_HOLDING = "holding"

    #: The motor is turning, but cannot reach its ``speed_sp``.
    STATE_OVERLOADED = "overloaded"

    #: The motor is not turning when it should be.
    STATE_STALLED = "stalled"

    #: Remove power; the motor coasts to a stop.
    STOP_ACTION_COAST = "coast"

    #: Remove power and short the motor's terminals, so it stops sooner than coasting.
    STOP_ACTION_BRAKE = "brake"

    #: Keep power on and actively hold the current position.
    STOP_ACTION_HOLD = "hold"

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._address = None
        self._command = None
        self._commands = None
        self._count_per_rot = None
        self._count_per_m = None
        self._driver_name = None
        self._duty_cycle = None
        self._duty_cycle_sp = None
        self._full_travel_count = None
        self._polarity = None
        self._position = None
        self._position_p = None
        self._position_i = None
        self._position_d = None
        self._position_sp = None
        self._max_speed = None
        self._speed = None
        self._speed_sp = None
        self._ramp_up_sp = None
        self._ramp_down_sp = None
        self._speed_p = None
        self._speed_i = None
        self._speed_d = None
        self._state = None
        self._stop_action = None
        self._stop_actions = None
        self._time_sp = None
        self._poll = None
        self.max_rps = float(self.max_speed / self.count_per_rot)
        self.max_rpm = self.max_rps * 60
        self.max_dps = self.max_rps * 360
        self.max_dpm = self.max_rpm * 360

    address = _attribute(
        "address", "The name of the port this motor is connected to.", kind="string", writable=False
    )
    command = _attribute(
        "command", "Sends a command to the motor controller; see ``commands``.", kind="string", readable=False
    )
    commands = _attribute(
        "commands",
        """
        The commands the motor controller supports: ``run-forever``, ``run-to-abs-pos``,
        ``run-to-rel-pos``, ``run-timed``, ``run-direct``, ``stop`` and ``reset``.
        """,
        kind="set",
        writable=False,
        cached=True,
    )
    count_per_rot = _attribute(
        "count_per_rot",
        "Tacho counts in one rotation of the motor (rotation motors).",
        writable=False,
        cached=True,
    )
    count_per_m = _attribute(
        "count_per_m", "Tacho counts in one meter of travel (linear motors).", writable=False, cached=True
    )
    driver_name = _attribute(
        "driver_name",
        "The name of the driver of this tacho motor.",
        kind="string",
        writable=False,
        cached=True,
    )
    duty_cycle = _attribute("duty_cycle", "The current duty cycle, in percent (-100 to 100).", writable=False)
    duty_cycle_sp = _attribute(
        "duty_cycle_sp", "The duty cycle setpoint for ``run-direct``, -100 to 100 percent."
    )
    full_travel_count = _attribute(
        "full_travel_count", "Tacho counts in the full travel (linear motors).", writable=False, cached=True
    )
    polarity = _attribute(
        "polarity", "``normal`` or ``inversed``: the direction a positive duty cycle turns.", kind="string"
    )
    position = _attribute("position", "The current position in tacho counts; writing sets it.")
    position_p = _attribute("hold_pid/Kp", "The proportional constant for the position PID.")
    position_i = _attribute("hold_pid/Ki", "The integral constant for the position PID.")
    position_d = _attribute("hold_pid/Kd", "The derivative constant for the position PID.")
    position_sp = _attribute(
        "position_sp", "The target position in tacho counts for the ``run-to-*-pos`` commands."
    )
    max_speed = _attribute(
        "max_speed",
        "The largest value ``speed_sp`` accepts, in tacho counts per second.",
        writable=False,
        cached=True,
    )
    speed = _attribute("speed", "The current speed in tacho counts per second.", writable=False)
    speed_sp = _attribute(
        "speed_sp",
        """
        The target speed in tacho counts per second for all ``run-*`` commands except
        ``run-direct``; negative runs in reverse (the sign is ignored by ``run-to-*-pos``).
        """,
    )
    ramp_up_sp = _attribute("ramp_up_sp", "Milliseconds to ramp from 0 to 100% of ``max_speed``.")
    ramp_down_sp = _attribute("ramp_down_sp", "Milliseconds to ramp from 100% of ``max_speed`` down to 0.")
    speed_p = _attribute("speed_pid/Kp", "The proportional constant for the speed regulation PID.")
    speed_i = _attribute("speed_pid/Ki", "The integral constant for the speed regulation PID.")
    speed_d = _attribute("speed_pid/Kd", "The derivative constant for the speed regulation PID.")
    state = _attribute(
        "state",
        "State flags: ``running``, ``ramping``, ``holding``, ``overloaded``, ``stalled``.",
        kind="set",
        writable=False,
    )
    stop_action = _attribute(
        "stop_action", "What the motor does when it stops: ``coast``, ``brake`` or ``hold``.", kind="string"
    )
    stop_actions = _attribute(
        "stop_actions", "The stop actions this motor supports.", kind="set", writable=False, cached=True
    )
    time_sp = _attribute("time_sp", "How long ``run-timed`` runs, in milliseconds.")

    def run_forever(self, **kwargs):
        """Run the motor until another command is sent."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_FOREVER

    def run_to_abs_pos(self, **kwargs):
        """Run to the absolute position ``position_sp``, then stop with ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_TO_ABS_POS

    def run_to_rel_pos(self, **kwargs):
        """Run to ``position`` + ``position_sp``, then stop with ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_TO_REL_POS

    def run_timed(self, **kwargs):
        """Run for ``time_sp`` milliseconds, then stop with ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_TIMED

    def run_direct(self, **kwargs):
        """Run at the duty cycle ``duty_cycle_sp``; changes to it take effect immediately."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_DIRECT

    def stop(self, **kwargs):
        """Stop any run command now, using ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_STOP

    def reset(self, **kwargs):
        """Reset all motor attributes to their defaults (this also stops the motor)."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RESET

    @property
    def is_running(self):
        """Power is being sent to the motor."""
        return self.STATE_RUNNING in self.state

    @property
    def is_ramping(self):
        """The motor is ramping up or down and has not yet reached a constant output level."""
        return self.STATE_RAMPING in self.state

    @property
    def is_holding(self):
        """The motor is not turning, but rather attempting to hold a fixed position."""
        return self.STATE_HOLDING in self.state

    @property
    def is_overloaded(self):
        """The motor is turning, but cannot reach its ``speed_sp``."""
        return self.STATE_OVERLOADED in self.state

    @property
    def is_stalled(self):
        """The motor is not turning when it should be."""
        return self.STATE_STALLED in self.state

    def wait(self, cond, timeout=None):
        """
        Blocks until ``cond(self.state)`` is ``True``, checking whenever the
        ``state`` attribute changes (and at least every 100 ms).  Returns
        ``False`` if ``timeout`` (milliseconds) passes first.
        """
        tic = time.time()

        if self._poll is None:
            if self._state is None:
                self._state = self._attribute_file_open("state")
            self._poll = True

        # Poll in short slices (see ev3dev-lang-python issue 583).
        if timeout:
            poll_tm = min(timeout, 100)
        else:
            poll_tm = 100

        while True:
            # This check is done every poll_tm even if poll has nothing to report:
            if cond(self.state):
                return True

            _link.poll(self._class_name, self._device_name, "state", poll_tm)

            if timeout is not None and time.time() >= tic + timeout / 1000:
                # Final check when user timeout is reached
                return cond(self.state)

    def wait_until_not_moving(self, timeout=None):
        """
        Blocks until ``running`` is not in ``self.state`` or ``stalled`` is;
        returns ``False`` if ``timeout`` (milliseconds) passes first.
        """
        return self.wait(
            lambda state: self.STATE_RUNNING not in state or self.STATE_STALLED in state, timeout
        )

    def wait_until(self, s, timeout=None):
        """Blocks until ``s`` is in ``self.state``, e.g. ``m.wait_until('stalled')``."""
        return self.wait(lambda state: s in state, timeout)

    def wait_while(self, s, timeout=None):
        """Blocks until ``s`` is not in ``self.state``, e.g. ``m.wait_while('running')``."""
        return self.wait(lambda state: s not in state, timeout)

    def _speed_native_units(self, speed, label=None):
        speed = speed_to_speedvalue(speed, label)
        return speed.to_native_units(self)

    def _set_rel_position_degrees_and_speed_sp(self, degrees, speed):
        # A negative speed turns a positive distance into a backwards one.
        degrees = degrees if speed >= 0 else -degrees
        speed = abs(speed)

        position_delta = int(round((degrees * self.count_per_rot) / 360))
        speed_sp = int(round(speed))

        self.position_sp = position_delta
        self.speed_sp = speed_sp

    def _set_brake(self, brake):
        if brake:
            self.stop_action = self.STOP_ACTION_HOLD
        else:
            self.stop_action = self.STOP_ACTION_COAST

    def on_for_rotations(self, speed, rotations, brake=True, block=True):
        """
        Rotate the motor at ``speed`` (percent or a SpeedValue) for ``rotations``.
        """
        speed_sp = self._speed_native_units(speed)
        self._set_rel_position_degrees_and_speed_sp(rotations * 360, speed_sp)
        self._set_brake(brake)
        self.run_to_rel_pos()

        if block:
            self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
            self.wait_until_not_moving()

    def on_for_degrees(self, speed, degrees, brake=True, block=True):
        """
        Rotate the motor at ``speed`` (percent or a SpeedValue) for ``degrees``.
        """
        speed_sp = self._speed_native_units(speed)
        self._set_rel_position_degrees_and_speed_sp(degrees, speed_sp)
        self._set_brake(brake)
        self.run_to_rel_pos()

        if block:
            self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
            self.wait_until_not_moving()

    def on_to_position(self, speed, position, brake=True, block=True):
        """
        Rotate the motor at ``speed`` (percent or a SpeedValue) to ``position`` (tacho counts).
        """
        speed = self._speed_native_units(speed)
        self.speed_sp = int(round(speed))
        self.position_sp = position
        self._set_brake(brake)
        self.run_to_abs_pos()

        if block:
            self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
            self.wait_until_not_moving()

    def on_for_seconds(self, speed, seconds, brake=True, block=True):
        """
        Rotate the motor at ``speed`` (percent or a SpeedValue) for ``seconds``.
        """
        if seconds < 0:
            raise ValueError(f"seconds is negative ({seconds})")

        speed = self._speed_native_units(speed)
        self.speed_sp = int(round(speed))
        self.time_sp = int(seconds * 1000)
        self._set_brake(brake)
        self.run_timed()

        if block:
            self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
            self.wait_until_not_moving()

    def on(self, speed, brake=True, block=False):
        """
        Rotate the motor at ``speed`` (percent or a SpeedValue) forever.

        Note that ``block`` is False by default, unlike the ``on_for_XYZ`` methods.
        """
        speed = self._speed_native_units(speed)
        self.speed_sp = int(round(speed))
        self._set_brake(brake)
        self.run_forever()

        if block:
            self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
            self.wait_until_not_moving()

    def off(self, brake=True):
        self._set_brake(brake)
        self.stop()

    @property
    def rotations(self):
        return float(self.position / self.count_per_rot)

    @property
    def degrees(self):
        return self.rotations * 360


def list_motors(name_pattern=Motor.SYSTEM_DEVICE_NAME_CONVENTION, **kwargs):
    """
    Generator of a ``Motor`` for every tacho motor matching ``name_pattern``
    and the keyword arguments, e.g. ``driver_name='lego-ev3-l-motor'`` or
    ``address=['outB', 'outC']``.
    """
    return (
        Motor(name_pattern=name, name_exact=True)
        for name in list_device_names(Motor.SYSTEM_CLASS_NAME, name_pattern, **kwargs)
    )


class LargeMotor(Motor):
    """EV3/NXT large servo motor: a :class:`Motor` that only accepts a large motor."""

    SYSTEM_CLASS_NAME = Motor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = "*"
    __slots__ = []

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(
            address, name_pattern, name_exact, driver_name=["lego-ev3-l-motor", "lego-nxt-motor"], **kwargs
        )


class MediumMotor(Motor):
    """EV3 medium servo motor: a :class:`Motor` that only accepts a medium motor."""

    SYSTEM_CLASS_NAME = Motor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = "*"
    __slots__ = []

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name=["lego-ev3-m-motor"], **kwargs)


class ActuonixL1250Motor(Motor):
    """Actuonix L12 50 linear servo motor."""

    SYSTEM_CLASS_NAME = Motor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = "linear*"
    __slots__ = []

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name=["act-l12-ev3-50"], **kwargs)


class ActuonixL12100Motor(Motor):
    """Actuonix L12 100 linear servo motor."""

    SYSTEM_CLASS_NAME = Motor.SYSTEM_CLASS_NAME
    SYSTEM_DEVICE_NAME_CONVENTION = "linear*"
    __slots__ = []

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):
        super().__init__(address, name_pattern, name_exact, driver_name=["act-l12-ev3-100"], **kwargs)


class DcMotor(Device):
    """
    A regular DC motor with no feedback, such as the RCX motors and
    LEGO Power Functions motors.
    """

    SYSTEM_CLASS_NAME = "dc-motor"
    SYSTEM_DEVICE_NAME_CONVENTION = "motor*"
    __slots__ = [
        "_address",
        "_command",
        "_commands",
        "_driver_name",
        "_duty_cycle",
        "_duty_cycle_sp",
        "_polarity",
        "_ramp_down_sp",
        "_ramp_up_sp",
        "_state",
        "_stop_action",
        "_stop_actions",
        "_time_sp",
    ]

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._address = None
        self._command = None
        self._commands = None
        self._driver_name = None
        self._duty_cycle = None
        self._duty_cycle_sp = None
        self._polarity = None
        self._ramp_down_sp = None
        self._ramp_up_sp = None
        self._state = None
        self._stop_action = None
        self._stop_actions = None
        self._time_sp = None

    address = _attribute(
        "address", "The name of the port this motor is connected to.", kind="string", writable=False
    )
    command = _attribute(
        "command",
        "Sends ``run-forever``, ``run-timed``, ``run-direct`` or ``stop``.",
        kind="string",
        readable=False,
    )
    commands = _attribute("commands", "The commands the motor supports.", kind="set", writable=False)
    driver_name = _attribute(
        "driver_name", "The name of the driver of this motor.", kind="string", writable=False
    )
    duty_cycle = _attribute("duty_cycle", "The current PWM duty cycle, -100 to 100 percent.", writable=False)
    duty_cycle_sp = _attribute("duty_cycle_sp", "The PWM duty cycle setpoint, -100 to 100 percent.")
    polarity = _attribute("polarity", "``normal`` or ``inversed``.", kind="string")
    ramp_down_sp = _attribute("ramp_down_sp", "Milliseconds to ramp down from 100% to 0% (0 to 10000).")
    ramp_up_sp = _attribute("ramp_up_sp", "Milliseconds to ramp up from 0% to 100% (0 to 10000).")
    state = _attribute("state", "State flags: ``running``, ``ramping``.", kind="set", writable=False)
    stop_action = _attribute(
        "stop_action",
        "The stop action used when the motor stops; see ``stop_actions``.",
        kind="string",
        readable=False,
    )
    stop_actions = _attribute(
        "stop_actions", "The stop actions: ``coast`` and ``brake``.", kind="set", writable=False
    )
    time_sp = _attribute("time_sp", "How long ``run-timed`` runs, in milliseconds.")

    #: Run the motor until another command is sent.
    COMMAND_RUN_FOREVER = "run-forever"

    #: Run for ``time_sp`` milliseconds, then stop with ``stop_action``.
    COMMAND_RUN_TIMED = "run-timed"

    #: Run at the duty cycle ``duty_cycle_sp``; changes to it take effect immediately.
    COMMAND_RUN_DIRECT = "run-direct"

    #: Stop any run command now, using ``stop_action``.
    COMMAND_STOP = "stop"

    #: With ``normal`` polarity, a positive duty cycle turns the motor clockwise.
    POLARITY_NORMAL = "normal"

    #: With ``inversed`` polarity, a positive duty cycle turns the motor counter-clockwise.
    POLARITY_INVERSED = "inversed"

    #: Remove power; the motor coasts to a stop.
    STOP_ACTION_COAST = "coast"

    #: Remove power and short the motor's terminals, so it stops sooner than coasting.
    STOP_ACTION_BRAKE = "brake"

    def run_forever(self, **kwargs):
        """Run the motor until another command is sent."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_FOREVER

    def run_timed(self, **kwargs):
        """Run for ``time_sp`` milliseconds, then stop with ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_TIMED

    def run_direct(self, **kwargs):
        """Run at the duty cycle ``duty_cycle_sp``; changes to it take effect immediately."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN_DIRECT

    def stop(self, **kwargs):
        """Stop any run command now, using ``stop_action``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_STOP


class ServoMotor(Device):
    """A hobby servo motor."""

    SYSTEM_CLASS_NAME = "servo-motor"
    SYSTEM_DEVICE_NAME_CONVENTION = "motor*"
    __slots__ = [
        "_address",
        "_command",
        "_driver_name",
        "_max_pulse_sp",
        "_mid_pulse_sp",
        "_min_pulse_sp",
        "_polarity",
        "_position_sp",
        "_rate_sp",
        "_state",
    ]

    def __init__(self, address=None, name_pattern=SYSTEM_DEVICE_NAME_CONVENTION, name_exact=False, **kwargs):

        if address is not None:
            kwargs["address"] = address
        super().__init__(self.SYSTEM_CLASS_NAME, name_pattern, name_exact, **kwargs)

        self._address = None
        self._command = None
        self._driver_name = None
        self._max_pulse_sp = None
        self._mid_pulse_sp = None
        self._min_pulse_sp = None
        self._polarity = None
        self._position_sp = None
        self._rate_sp = None
        self._state = None

    address = _attribute(
        "address", "The name of the port this motor is connected to.", kind="string", writable=False
    )
    command = _attribute(
        "command",
        "``run`` drives to ``position_sp``; ``float`` removes power.",
        kind="string",
        readable=False,
    )
    driver_name = _attribute(
        "driver_name", "The name of the driver of this motor.", kind="string", writable=False
    )
    max_pulse_sp = _attribute(
        "max_pulse_sp", "Pulse (ms) for the maximum (clockwise) position; 2300 to 2700."
    )
    mid_pulse_sp = _attribute("mid_pulse_sp", "Pulse (ms) for the middle position; 1300 to 1700.")
    min_pulse_sp = _attribute(
        "min_pulse_sp", "Pulse (ms) for the minimum (counter-clockwise) position; 300 to 700."
    )
    polarity = _attribute(
        "polarity", "``normal`` or ``inversed`` (inversed swaps min and max).", kind="string"
    )
    position_sp = _attribute(
        "position_sp", "The target position, -100 to 100 percent; writing moves the servo."
    )
    rate_sp = _attribute("rate_sp", "Milliseconds to travel from 0 to 100% (half the servo's range).")
    state = _attribute("state", "State flags: ``running``.", kind="set", writable=False)

    #: Drive servo to the position set in the ``position_sp`` attribute.
    COMMAND_RUN = "run"

    #: Remove power from the motor.
    COMMAND_FLOAT = "float"

    #: With ``normal`` polarity, a positive duty cycle turns the motor clockwise.
    POLARITY_NORMAL = "normal"

    #: With ``inversed`` polarity, a positive duty cycle turns the motor counter-clockwise.
    POLARITY_INVERSED = "inversed"

    def run(self, **kwargs):
        """Drive the servo to ``position_sp``."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_RUN

    def float(self, **kwargs):
        """Remove power from the motor."""
        for key in kwargs:
            setattr(self, key, kwargs[key])
        self.command = self.COMMAND_FLOAT


class MotorSet:
    """Several motors driven together; ``motor_specs`` maps ports to motor classes."""

    def __init__(self, motor_specs, desc=None):
        """
        motor_specs is a dictionary such as ``{OUTPUT_A: LargeMotor, OUTPUT_C: LargeMotor}``.
        The motors are made, and reset, in port order.
        """
        self.motors = OrderedDict()
        for motor_port in sorted(motor_specs.keys()):
            motor_class = motor_specs[motor_port]
            self.motors[motor_port] = motor_class(motor_port)
            self.motors[motor_port].reset()

        self.desc = desc

    def __str__(self):
        if self.desc:
            return self.desc
        else:
            return self.__class__.__name__

    def set_args(self, **kwargs):
        motors = kwargs.get("motors", self.motors.values())

        for motor in motors:
            for key in kwargs:
                if key != "motors":
                    setattr(motor, key, kwargs[key])

    def set_polarity(self, polarity, motors=None):
        valid_choices = (LargeMotor.POLARITY_NORMAL, LargeMotor.POLARITY_INVERSED)

        assert polarity in valid_choices, "{} is an invalid polarity choice, must be {}".format(
            polarity, ", ".join(valid_choices)
        )
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.polarity = polarity

    def _run_command(self, **kwargs):
        motors = kwargs.get("motors", self.motors.values())

        for motor in motors:
            for key in kwargs:
                if key not in ("motors", "commands"):
                    setattr(motor, key, kwargs[key])

        for motor in motors:
            motor.command = kwargs["command"]

    def run_forever(self, **kwargs):
        kwargs["command"] = LargeMotor.COMMAND_RUN_FOREVER
        self._run_command(**kwargs)

    def run_to_abs_pos(self, **kwargs):
        kwargs["command"] = LargeMotor.COMMAND_RUN_TO_ABS_POS
        self._run_command(**kwargs)

    def run_to_rel_pos(self, **kwargs):
        kwargs["command"] = LargeMotor.COMMAND_RUN_TO_REL_POS
        self._run_command(**kwargs)

    def run_timed(self, **kwargs):
        kwargs["command"] = LargeMotor.COMMAND_RUN_TIMED
        self._run_command(**kwargs)

    def run_direct(self, **kwargs):
        kwargs["command"] = LargeMotor.COMMAND_RUN_DIRECT
        self._run_command(**kwargs)

    def reset(self, motors=None):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.reset()

    def off(self, motors=None, brake=True):
        """Stop the motors now; they hold their position if ``brake`` is set, else coast."""
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor._set_brake(brake)

        for motor in motors:
            motor.stop()

    def stop(self, motors=None, brake=True):
        """Deprecated alias of ``off``."""
        self.off(motors, brake)

    def _is_state(self, motors, state):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            if state not in motor.state:
                return False

        return True

    @property
    def is_running(self, motors=None):
        return self._is_state(motors, LargeMotor.STATE_RUNNING)

    @property
    def is_ramping(self, motors=None):
        return self._is_state(motors, LargeMotor.STATE_RAMPING)

    @property
    def is_holding(self, motors=None):
        return self._is_state(motors, LargeMotor.STATE_HOLDING)

    @property
    def is_overloaded(self, motors=None):
        return self._is_state(motors, LargeMotor.STATE_OVERLOADED)

    @property
    def is_stalled(self, motors=None):
        return self._is_state(motors, LargeMotor.STATE_STALLED)

    def wait(self, cond, timeout=None, motors=None):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.wait(cond, timeout)

    def wait_until_not_moving(self, timeout=None, motors=None):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.wait_until_not_moving(timeout)

    def wait_until(self, s, timeout=None, motors=None):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.wait_until(s, timeout)

    def wait_while(self, s, timeout=None, motors=None):
        motors = motors if motors is not None else self.motors.values()

        for motor in motors:
            motor.wait_while(s, timeout)

    def _block(self):
        self.wait_until("running", timeout=WAIT_RUNNING_TIMEOUT)
        self.wait_until_not_moving()


class FollowGyroAngleErrorTooFast(Exception):
    """A gyro-following robot was asked to follow an angle at an unrealistic speed."""

    pass


class LineFollowErrorLostLine(Exception):
    """A line-following robot has lost the line."""

    pass


class LineFollowErrorTooFast(Exception):
    """A line-following robot was asked to follow a line at an unrealistic speed."""

    pass


def follow_for_forever(tank):
    """``follow_for`` that never ends the following."""
    return True


def follow_for_ms(tank, ms):
    """``follow_for`` that ends the following after ``ms`` milliseconds."""
    if not hasattr(tank, "stopwatch") or tank.stopwatch is None:
        tank.stopwatch = StopWatch()
        tank.stopwatch.start()

    if tank.stopwatch.value_ms >= ms:
        tank.stopwatch = None
        return False
    else:
        return True


class MoveTank(MotorSet):
    """
    A pair of motors driven with one speed each.

    Example::

        tank_drive = MoveTank(OUTPUT_A, OUTPUT_B)
        # drive in a turn for 10 rotations of the outer motor
        tank_drive.on_for_rotations(50, 75, 10)
    """

    def __init__(self, left_motor_port, right_motor_port, desc=None, motor_class=LargeMotor):
        motor_specs = {
            left_motor_port: motor_class,
            right_motor_port: motor_class,
        }

        MotorSet.__init__(self, motor_specs, desc)
        self.left_motor = self.motors[left_motor_port]
        self.right_motor = self.motors[right_motor_port]
        self.max_speed = self.left_motor.max_speed
        self._cs = None
        self._gyro = None

    # color sensor used by follow_line()
    @property
    def cs(self):
        return self._cs

    @cs.setter
    def cs(self, cs):
        self._cs = cs

    # gyro sensor used by follow_gyro_angle()
    @property
    def gyro(self):
        return self._gyro

    @gyro.setter
    def gyro(self, gyro):
        self._gyro = gyro

    def _unpack_speeds_to_native_units(self, left_speed, right_speed):
        left_speed = self.left_motor._speed_native_units(left_speed, "left_speed")
        right_speed = self.right_motor._speed_native_units(right_speed, "right_speed")

        return (left_speed, right_speed)

    def on_for_degrees(self, left_speed, right_speed, degrees, brake=True, block=True):
        """
        Rotate the motors at ``left_speed`` and ``right_speed`` for ``degrees``.

        The faster motor turns the full ``degrees``; the slower one turns
        proportionally less, so both finish together.
        """
        (left_speed_native_units, right_speed_native_units) = self._unpack_speeds_to_native_units(
            left_speed, right_speed
        )

        # Both wheels run for the same time t = d_l / v_l = d_r / v_r.
        if degrees == 0 or (left_speed_native_units == 0 and right_speed_native_units == 0):
            left_degrees = degrees
            right_degrees = degrees

        # larger speed by magnitude is the "outer" wheel, and rotates the full "degrees"
        elif abs(left_speed_native_units) > abs(right_speed_native_units):
            left_degrees = degrees
            right_degrees = abs(right_speed_native_units / left_speed_native_units) * degrees

        else:
            left_degrees = abs(left_speed_native_units / right_speed_native_units) * degrees
            right_degrees = degrees

        # Set all parameters
        self.left_motor._set_rel_position_degrees_and_speed_sp(left_degrees, left_speed_native_units)
        self.left_motor._set_brake(brake)
        self.right_motor._set_rel_position_degrees_and_speed_sp(right_degrees, right_speed_native_units)
        self.right_motor._set_brake(brake)

        # Start the motors
        self.left_motor.run_to_rel_pos()
        self.right_motor.run_to_rel_pos()

        if block:
            self._block()

    def on_for_rotations(self, left_speed, right_speed, rotations, brake=True, block=True):
        """
        Rotate the motors at ``left_speed`` and ``right_speed`` for ``rotations``
        (the faster motor turns the full amount, as in ``on_for_degrees``).
        """
        MoveTank.on_for_degrees(self, left_speed, right_speed, rotations * 360, brake, block)

    def on_for_seconds(self, left_speed, right_speed, seconds, brake=True, block=True):
        """Rotate the motors at ``left_speed`` and ``right_speed`` for ``seconds``."""
        if seconds < 0:
            raise ValueError(f"seconds is negative ({seconds})")

        (left_speed_native_units, right_speed_native_units) = self._unpack_speeds_to_native_units(
            left_speed, right_speed
        )

        # Set all parameters
        self.left_motor.speed_sp = int(round(left_speed_native_units))
        self.left_motor.time_sp = int(seconds * 1000)
        self.left_motor._set_brake(brake)
        self.right_motor.speed_sp = int(round(right_speed_native_units))
        self.right_motor.time_sp = int(seconds * 1000)
        self.right_motor._set_brake(brake)

        log.debug(f"{self}: on_for_seconds {seconds}s at left-speed {left_speed}, right-speed {right_speed}")

        # Start the motors
        self.left_motor.run_timed()
        self.right_motor.run_timed()

        if block:
            self._block()

    def on(self, left_speed, right_speed):
        """Start the motors at ``left_speed`` and ``right_speed``, forever."""
        (left_speed_native_units, right_speed_native_units) = self._unpack_speeds_to_native_units(
            left_speed, right_speed
        )

        # Set all parameters
        self.left_motor.speed_sp = int(round(left_speed_native_units))
        self.right_motor.speed_sp = int(round(right_speed_native_units))

        # Start the motors
        self.left_motor.run_forever()
        self.right_motor.run_forever()

    def follow_line(
        self,
        kp,
        ki,
        kd,
        speed,
        target_light_intensity=None,
        follow_left_edge=True,
        white=60,
        off_line_count_max=20,
        sleep_time=0.01,
        follow_for=follow_for_forever,
        **kwargs,
    ):
        """
        PID line follower using the colour sensor ``self.cs``.

        ``kp``, ``ki``, ``kd``: PID constants; ``speed``: speed of the robot's
        middle; ``target_light_intensity``: reading on the line's edge (None:
        read it now); ``follow_left_edge``: which edge; ``white``: readings at
        or above this are off the line, and ``off_line_count_max`` of them in a
        row raise LineFollowErrorLostLine; ``sleep_time``: seconds per loop;
        ``follow_for(self, **kwargs)``: keep following while it returns True
        (``follow_for_forever``, ``follow_for_ms``).

        Example::

            tank.cs = ColorSensor()
            tank.follow_line(kp=11.3, ki=0.05, kd=3.2, speed=SpeedPercent(30),
                             follow_for=follow_for_ms, ms=4500)
        """
        if not self._cs:
            raise DeviceNotDefined(
                "The 'cs' variable must be defined with a ColorSensor. Example: tank.cs = ColorSensor()"
            )

        if target_light_intensity is None:
            target_light_intensity = self._cs.reflected_light_intensity

        integral = 0.0
        last_error = 0.0
        derivative = 0.0
        off_line_count = 0
        speed = speed_to_speedvalue(speed)
        speed_native_units = speed.to_native_units(self.left_motor)

        while follow_for(self, **kwargs):
            reflected_light_intensity = self._cs.reflected_light_intensity
            error = target_light_intensity - reflected_light_intensity
            integral = integral + error
            derivative = error - last_error
            last_error = error
            turn_native_units = (kp * error) + (ki * integral) + (kd * derivative)

            if not follow_left_edge:
                turn_native_units *= -1

            left_speed = SpeedNativeUnits(speed_native_units - turn_native_units)
            right_speed = SpeedNativeUnits(speed_native_units + turn_native_units)

            # Have we lost the line?
            if reflected_light_intensity >= white:
                off_line_count += 1

                if off_line_count >= off_line_count_max:
                    self.stop()
                    raise LineFollowErrorLostLine("we lost the line")
            else:
                off_line_count = 0

            if sleep_time:
                time.sleep(sleep_time)

            try:
                self.on(left_speed, right_speed)
            except SpeedInvalid as e:
                log.exception(e)
                self.stop()
                raise LineFollowErrorTooFast("The robot is moving too fast to follow the line")  # noqa: B904  (as upstream)

        self.stop()

    def follow_gyro_angle(
        self, kp, ki, kd, speed, target_angle=0, sleep_time=0.01, follow_for=follow_for_forever, **kwargs
    ):
        """
        PID gyro angle follower using the gyro sensor ``self.gyro``: drive at
        ``speed`` keeping the gyro at ``target_angle``; ``follow_for`` as in
        ``follow_line``.

        Example::

            tank.gyro = GyroSensor()
            tank.gyro.calibrate()
            tank.follow_gyro_angle(kp=11.3, ki=0.05, kd=3.2, speed=SpeedPercent(30),
                                   target_angle=0, follow_for=follow_for_ms, ms=4500)
        """
        if not self._gyro:
            raise DeviceNotDefined(
                "The 'gyro' variable must be defined with a GyroSensor. Example: tank.gyro = GyroSensor()"
            )

        integral = 0.0
        last_error = 0.0
        derivative = 0.0
        speed = speed_to_speedvalue(speed)
        speed_native_units = speed.to_native_units(self.left_motor)

        while follow_for(self, **kwargs):
            current_angle = self._gyro.angle
            error = current_angle - target_angle
            integral = integral + error
            derivative = error - last_error
            last_error = error
            turn_native_units = (kp * error) + (ki * integral) + (kd * derivative)

            left_speed = SpeedNativeUnits(speed_native_units - turn_native_units)
            right_speed = SpeedNativeUnits(speed_native_units + turn_native_units)

            if sleep_time:
                time.sleep(sleep_time)

            try:
                self.on(left_speed, right_speed)
            except SpeedInvalid as e:
                log.exception(e)
                self.stop()
                raise FollowGyroAngleErrorTooFast("The robot is moving too fast to follow the angle")  # noqa: B904

        self.stop()

    def turn_degrees(self, speed, target_angle, brake=True, error_margin=2, sleep_time=0.01):
        """
        Rotate in place by ``target_angle`` degrees (positive: clockwise), using
        the gyro sensor ``self.gyro``, until within ``error_margin`` degrees.

        Example::

            tank.gyro = GyroSensor()
            tank.gyro.calibrate()
            tank.turn_degrees(speed=SpeedPercent(5), target_angle=30)
        """
        # MoveTank knows nothing of wheel size and spacing (MoveDifferential
        # does), so a GyroSensor measures how far we have rotated.
        if not self._gyro:
            raise DeviceNotDefined(
                "The 'gyro' variable must be defined with a GyroSensor. Example: tank.gyro = GyroSensor()"
            )

        speed = speed_to_speedvalue(speed)
        speed_native_units = speed.to_native_units(self.left_motor)
        target_angle = self._gyro.angle + target_angle

        while True:
            current_angle = self._gyro.angle
            delta = abs(target_angle - current_angle)

            if delta <= error_margin:
                self.stop(brake=brake)
                break

            # we are left of our target, rotate clockwise
            if current_angle < target_angle:
                left_speed = SpeedNativeUnits(speed_native_units)
                right_speed = SpeedNativeUnits(-1 * speed_native_units)

            # we are right of our target, rotate counter-clockwise
            else:
                left_speed = SpeedNativeUnits(-1 * speed_native_units)
                right_speed = SpeedNativeUnits(speed_native_units)

            self.on(left_speed, right_speed)

            if sleep_time:
                time.sleep(sleep_time)

    def turn_right(self, speed, degrees, brake=True, error_margin=2, sleep_time=0.01):
        """Rotate clockwise ``degrees`` in place (uses the gyro)."""
        self.turn_degrees(speed, abs(degrees), brake, error_margin, sleep_time)

    def turn_left(self, speed, degrees, brake=True, error_margin=2, sleep_time=0.01):
        """Rotate counter-clockwise ``degrees`` in place (uses the gyro)."""
        self.turn_degrees(speed, abs(degrees) * -1, brake, error_margin, sleep_time)


class MoveSteering(MoveTank):
    """
    A pair of motors driven with one "steering" value and one speed.

    steering [-100, 100]: -100 turns left on the spot (right motor forward,
    left backward), 0 drives straight, 100 turns right on the spot.  The
    outer motor runs at ``speed``; the inner one at speed * (50 - |steering|) / 50.

    Example::

        steering_drive = MoveSteering(OUTPUT_A, OUTPUT_B)
        # drive in a turn for 10 rotations of the outer motor
        steering_drive.on_for_rotations(-20, SpeedPercent(75), 10)
    """

    def on_for_rotations(self, steering, speed, rotations, brake=True, block=True):
        """Rotate the motors according to ``steering`` for ``rotations`` of the outer motor."""
        (left_speed, right_speed) = self.get_speed_steering(steering, speed)
        MoveTank.on_for_rotations(
            self, SpeedNativeUnits(left_speed), SpeedNativeUnits(right_speed), rotations, brake, block
        )

    def on_for_degrees(self, steering, speed, degrees, brake=True, block=True):
        """Rotate the motors according to ``steering`` for ``degrees`` of the outer motor."""
        (left_speed, right_speed) = self.get_speed_steering(steering, speed)
        MoveTank.on_for_degrees(
            self, SpeedNativeUnits(left_speed), SpeedNativeUnits(right_speed), degrees, brake, block
        )

    def on_for_seconds(self, steering, speed, seconds, brake=True, block=True):
        """Rotate the motors according to ``steering`` for ``seconds``."""
        (left_speed, right_speed) = self.get_speed_steering(steering, speed)
        MoveTank.on_for_seconds(
            self, SpeedNativeUnits(left_speed), SpeedNativeUnits(right_speed), seconds, brake, block
        )

    def on(self, steering, speed):
        """Start the motors according to ``steering`` and ``speed``, forever."""
        (left_speed, right_speed) = self.get_speed_steering(steering, speed)
        MoveTank.on(self, SpeedNativeUnits(left_speed), SpeedNativeUnits(right_speed))

    def get_speed_steering(self, steering, speed):
        """
        The (left, right) speeds, in native units, for ``steering`` and
        ``speed`` (the speed of the outer motor).  Does not move the motors.
        """
        assert steering >= -100 and steering <= 100, (
            f"{steering} is an invalid steering, must be between -100 and 100 (inclusive)"
        )

        # Assumes both motors have the left motor's speed range, as upstream.
        speed = self.left_motor._speed_native_units(speed)
        left_speed = speed
        right_speed = speed
        speed_factor = (50 - abs(float(steering))) / 50

        if steering >= 0:
            right_speed *= speed_factor
        else:
            left_speed *= speed_factor

        return (left_speed, right_speed)


class MoveDifferential(MoveTank):
    """
    A MoveTank that knows its wheels (``wheel_class``, e.g. ``EV3Tire``) and
    the distance between their middles (``wheel_distance_mm``), so it can
    drive distances, arcs and turns, and track its position by odometry.

    Example::

        mdiff = MoveDifferential(OUTPUT_A, OUTPUT_B, EV3Tire, 16 * STUD_MM)
        mdiff.turn_right(SpeedRPM(40), 90)            # rotate 90 degrees clockwise
        mdiff.on_for_distance(SpeedRPM(40), 500)      # drive forward 500 mm
        mdiff.on_arc_right(SpeedRPM(80), 150, 700)    # 700 mm along a circle of radius 150 mm
        mdiff.odometry_start()
        mdiff.on_to_coordinates(SpeedRPM(40), 300, 300)
        mdiff.turn_to_angle(SpeedRPM(40), 90)
        mdiff.odometry_stop()
    """

    def __init__(
        self,
        left_motor_port,
        right_motor_port,
        wheel_class,
        wheel_distance_mm,
        desc=None,
        motor_class=LargeMotor,
    ):

        MoveTank.__init__(self, left_motor_port, right_motor_port, desc, motor_class)
        self.wheel = wheel_class()
        self.wheel_distance_mm = wheel_distance_mm

        # The circumference of the circle made if this robot were to rotate in place
        self.circumference_mm = self.wheel_distance_mm * math.pi

        self.min_circle_radius_mm = self.wheel_distance_mm / 2

        # odometry variables
        self.x_pos_mm = 0.0  # robot X position in mm
        self.y_pos_mm = 0.0  # robot Y position in mm
        self.odometry_thread_run = False
        self.theta = 0.0

    def on_for_distance(self, speed, distance_mm, brake=True, block=True):
        """Drive in a straight line for ``distance_mm``."""
        rotations = distance_mm / self.wheel.circumference_mm
        log.debug(f"{self}: on_for_rotations distance_mm {distance_mm}, rotations {rotations}, speed {speed}")

        MoveTank.on_for_rotations(self, speed, speed, rotations, brake, block)

    def _on_arc(self, speed, radius_mm, distance_mm, brake, block, arc_right):
        """Drive ``distance_mm`` along a circle of ``radius_mm`` (measured to the robot's middle)."""
        if radius_mm < self.min_circle_radius_mm:
            raise ValueError(
                f"{self}: radius_mm {radius_mm} is less than min_circle_radius_mm {self.min_circle_radius_mm}"
            )

        # The circle formed at the halfway point between the two wheels is the
        # circle that must have a radius of radius_mm
        circle_outer_mm = 2 * math.pi * (radius_mm + (self.wheel_distance_mm / 2))
        circle_middle_mm = 2 * math.pi * radius_mm
        circle_inner_mm = 2 * math.pi * (radius_mm - (self.wheel_distance_mm / 2))

        if arc_right:
            # The left wheel is on the outer circle and moves at 'speed'
            left_speed = speed
            right_speed = float(circle_inner_mm / circle_outer_mm) * left_speed

        else:
            # The right wheel is on the outer circle and moves at 'speed'
            right_speed = speed
            left_speed = float(circle_inner_mm / circle_outer_mm) * right_speed

        log.debug(
            "{}: arc {}, radius {}, distance {}, left-speed {}, right-speed {}".format(
                self, "right" if arc_right else "left", radius_mm, distance_mm, left_speed, right_speed
            )
        )

        # The fraction of the middle circle to travel, applied to the outer circle
        circle_middle_percentage = float(distance_mm / circle_middle_mm)
        circle_outer_final_mm = circle_middle_percentage * circle_outer_mm

        outer_wheel_rotations = float(circle_outer_final_mm / self.wheel.circumference_mm)
        outer_wheel_degrees = outer_wheel_rotations * 360

        log.debug(
            f"{self}: outer_wheel_rotations {outer_wheel_rotations}, outer_wheel_degrees {outer_wheel_degrees}"
        )

        MoveTank.on_for_degrees(self, left_speed, right_speed, outer_wheel_degrees, brake, block)

    def on_arc_right(self, speed, radius_mm, distance_mm, brake=True, block=True):
        """Drive clockwise along a circle of ``radius_mm`` for ``distance_mm``."""
        self._on_arc(speed, radius_mm, distance_mm, brake, block, True)

    def on_arc_left(self, speed, radius_mm, distance_mm, brake=True, block=True):
        """Drive counter-clockwise along a circle of ``radius_mm`` for ``distance_mm``."""
        self._on_arc(speed, radius_mm, distance_mm, brake, block, False)

    def turn_degrees(self, speed, degrees, brake=True, block=True, error_margin=2, use_gyro=False):
        """
        Rotate in place ``degrees`` (positive: clockwise).  With ``use_gyro``,
        ``brake`` and ``block`` all True and ``self.gyro`` set, the gyro checks
        the turn and corrects errors above ``error_margin``.
        """

        def final_angle(init_angle, degrees):
            result = init_angle - degrees

            while result <= -360:
                result += 360

            while result >= 360:
                result -= 360

            if result < 0:
                result += 360

            return result

        # use the gyro to check that we turned the correct amount?
        use_gyro = bool(use_gyro and block and brake)
        if use_gyro and not self._gyro:
            raise DeviceNotDefined(
                "The 'gyro' variable must be defined with a GyroSensor. Example: tank.gyro = GyroSensor()"
            )

        if use_gyro:
            angle_init_degrees = self._gyro.circle_angle()
        else:
            angle_init_degrees = math.degrees(self.theta)

        angle_target_degrees = final_angle(angle_init_degrees, degrees)

        log.info(
            f"{self}: turn_degrees() {int(degrees)} degrees from {angle_init_degrees} to {angle_target_degrees}"
        )

        # The distance each wheel needs to travel
        distance_mm = (abs(degrees) / 360) * self.circumference_mm

        # The number of rotations to move distance_mm
        rotations = distance_mm / self.wheel.circumference_mm

        # If degrees is positive rotate clockwise
        if degrees > 0:
            MoveTank.on_for_rotations(self, speed, speed * -1, rotations, brake, block)

        # If degrees is negative rotate counter-clockwise
        else:
            MoveTank.on_for_rotations(self, speed * -1, speed, rotations, brake, block)

        if use_gyro:
            angle_current_degrees = self._gyro.circle_angle()

            # Aiming for 2 degrees and overrotated to 358: rotate counter-clockwise
            if 90 >= angle_target_degrees >= 0 and 270 <= angle_current_degrees <= 360:
                degrees_error = (angle_target_degrees + (360 - angle_current_degrees)) * -1

            # Aiming for 358 degrees and overrotated to 2: rotate clockwise
            elif 360 >= angle_target_degrees >= 270 and 0 <= angle_current_degrees <= 90:
                degrees_error = angle_current_degrees + (360 - angle_target_degrees)

            # We need to rotate clockwise
            elif angle_current_degrees > angle_target_degrees:
                degrees_error = angle_current_degrees - angle_target_degrees

            # We need to rotate counter-clockwise
            else:
                degrees_error = (angle_target_degrees - angle_current_degrees) * -1

            log.info(
                f"{self}: turn_degrees() ended up at {angle_current_degrees}, error {degrees_error}, error_margin {error_margin}"
            )

            if abs(degrees_error) > error_margin:
                self.turn_degrees(speed, degrees_error, brake, block, error_margin, use_gyro)

    def turn_right(self, speed, degrees, brake=True, block=True, error_margin=2, use_gyro=False):
        """Rotate clockwise ``degrees`` in place."""
        self.turn_degrees(speed, abs(degrees), brake, block, error_margin, use_gyro)

    def turn_left(self, speed, degrees, brake=True, block=True, error_margin=2, use_gyro=False):
        """Rotate counter-clockwise ``degrees`` in place."""
        self.turn_degrees(speed, abs(degrees) * -1, brake, block, error_margin, use_gyro)

    def turn_to_angle(
        self, speed, angle_target_degrees, brake=True, block=True, error_margin=2, use_gyro=False
    ):
        """Rotate in place to the odometry heading ``angle_target_degrees`` (needs odometry_start())."""
        if not self.odometry_thread_run:
            raise ThreadNotRunning("odometry_start() must be called to track robot coordinates")

        # Make both target and current angles positive numbers between 0 and 360
        while angle_target_degrees < 0:
            angle_target_degrees += 360

        angle_current_degrees = math.degrees(self.theta)

        while angle_current_degrees < 0:
            angle_current_degrees += 360

        # Is it shorter to rotate to the right or left
        # to reach angle_target_degrees?
        if angle_current_degrees > angle_target_degrees:
            turn_right = True
            angle_delta = angle_current_degrees - angle_target_degrees
        else:
            turn_right = False
            angle_delta = angle_target_degrees - angle_current_degrees

        if angle_delta > 180:
            angle_delta = 360 - angle_delta
            turn_right = not turn_right

        log.debug(
            f"{self}: turn_to_angle {angle_target_degrees}, current angle {angle_current_degrees}, delta {angle_delta}, turn_right {turn_right}"
        )
        self.odometry_coordinates_log()

        if turn_right:
            self.turn_degrees(speed, abs(angle_delta), brake, block, error_margin, use_gyro)
        else:
            self.turn_degrees(speed, abs(angle_delta) * -1, brake, block, error_margin, use_gyro)

        self.odometry_coordinates_log()

    def odometry_coordinates_log(self):
        log.debug(
            f"{self}: odometry angle {math.degrees(self.theta)} at ({int(self.x_pos_mm)}, {int(self.y_pos_mm)})"
        )

    def odometry_start(
        self, theta_degrees_start=90.0, x_pos_start=0.0, y_pos_start=0.0, sleep_time=0.005
    ):  # 5ms
        """
        Start a thread that tracks the robot's position (``x_pos_mm``,
        ``y_pos_mm``) and heading (``theta``, radians) from the wheel encoders,
        until odometry_stop().  Ported from David Anderson's "IMU Odometry":
        http://seattlerobotics.org/encoder/200610/Article3/IMU%20Odometry,%20by%20David%20Anderson.htm
        """

        def _odometry_monitor():
            left_previous = 0
            right_previous = 0
            self.theta = math.radians(theta_degrees_start)  # robot heading
            self.x_pos_mm = x_pos_start  # robot X position in mm
            self.y_pos_mm = y_pos_start  # robot Y position in mm
            TWO_PI = 2 * math.pi
            self.odometry_thread_run = True

            while self.odometry_thread_run:
                # sample the left and right encoder counts as close together
                # in time as possible
                left_current = self.left_motor.position
                right_current = self.right_motor.position

                # determine how many ticks since our last sampling
                left_ticks = left_current - left_previous
                right_ticks = right_current - right_previous

                # Have we moved?
                if not left_ticks and not right_ticks:
                    if sleep_time:
                        time.sleep(sleep_time)
                    continue

                # update _previous for next time
                left_previous = left_current
                right_previous = right_current

                # rotations = distance_mm/self.wheel.circumference_mm
                left_rotations = float(left_ticks / self.left_motor.count_per_rot)
                right_rotations = float(right_ticks / self.right_motor.count_per_rot)

                # convert longs to floats and ticks to mm
                left_mm = float(left_rotations * self.wheel.circumference_mm)
                right_mm = float(right_rotations * self.wheel.circumference_mm)

                # calculate distance we have traveled since last sampling
                mm = (left_mm + right_mm) / 2.0

                # accumulate total rotation around our center
                self.theta += (right_mm - left_mm) / self.wheel_distance_mm

                # and clip the rotation to plus or minus 360 degrees
                self.theta -= float(int(self.theta / TWO_PI) * TWO_PI)

                # now calculate and accumulate our position in mm
                self.x_pos_mm += mm * math.cos(self.theta)
                self.y_pos_mm += mm * math.sin(self.theta)

                if sleep_time:
                    time.sleep(sleep_time)

        _thread.start_new_thread(_odometry_monitor, ())

        # Block until the thread has started doing work.  Upstream spins with
        # `pass`; sleep(0) lets a scheduler that runs one thread at a time
        # switch to the new thread (it costs no virtual time).
        while not self.odometry_thread_run:
            time.sleep(0)

    def odometry_stop(self):
        """Signal the odometry thread to exit."""
        if self.odometry_thread_run:
            self.odometry_thread_run = False

    def on_to_coordinates(self, speed, x_target_mm, y_target_mm, brake=True, block=True):
        """Turn towards (``x_target_mm``, ``y_target_mm``) and drive there (needs odometry_start())."""
        if not self.odometry_thread_run:
            raise ThreadNotRunning("odometry_start() must be called to track robot coordinates")

        # stop moving
        self.off(brake="hold")

        # rotate in place so we are pointed straight at our target
        x_delta = x_target_mm - self.x_pos_mm
        y_delta = y_target_mm - self.y_pos_mm
        angle_target_radians = math.atan2(y_delta, x_delta)
        angle_target_degrees = math.degrees(angle_target_radians)
        self.turn_to_angle(speed, angle_target_degrees, brake=True, block=True)

        # drive in a straight line to the target coordinates
        distance_mm = math.sqrt(pow(self.x_pos_mm - x_target_mm, 2) + pow(self.y_pos_mm - y_target_mm, 2))
        self.on_for_distance(speed, distance_mm, brake, block)


class MoveJoystick(MoveTank):
    """A pair of motors driven by one joystick vector."""

    def on(self, x, y, radius=100.0):
        """
        Drive by joystick position (``x``, ``y``), (0, 0) being the centre and
        ``radius`` the joystick's range, with the classic "arcade drive": full
        forward drives straight ahead, full to one side turns on the spot.
        """
        # If joystick is in the middle stop the tank
        if not x and not y:
            self.off()
            return

        vector_length = math.sqrt((x * x) + (y * y))
        angle = math.degrees(math.atan2(y, x))

        if angle < 0:
            angle += 360

        # Should not happen but can happen (just by a hair) due to floating point math
        if vector_length > radius:
            vector_length = radius

        (init_left_speed_percentage, init_right_speed_percentage) = MoveJoystick.angle_to_speed_percentage(
            angle
        )

        # scale the speed percentages based on vector_length vs. radius
        left_speed_percentage = (init_left_speed_percentage * vector_length) / radius
        right_speed_percentage = (init_right_speed_percentage * vector_length) / radius

        MoveTank.on(self, SpeedPercent(left_speed_percentage), SpeedPercent(right_speed_percentage))

    @staticmethod
    def angle_to_speed_percentage(angle):
        """
        The (left, right) motor percentages for a joystick at ``angle`` degrees
        from the x-axis: 90 gives (100, 100), 0 gives (100, -100), 45 gives
        (100, 0), 180 gives (-100, 100), 270 gives (-100, -100); in between,
        each motor moves linearly between these points (see upstream's
        diagram in the python-ev3dev2 documentation).
        """
        if 0 <= angle <= 45:
            # left motor stays at 1
            left_speed_percentage = 1

            # right motor transitions from -1 to 0
            right_speed_percentage = -1 + (angle / 45.0)

        elif 45 < angle <= 90:
            # left motor stays at 1
            left_speed_percentage = 1

            # right motor transitions from 0 to 1
            percentage_from_45_to_90 = (angle - 45) / 45.0
            right_speed_percentage = percentage_from_45_to_90

        elif 90 < angle <= 135:
            # left motor transitions from 1 to 0
            percentage_from_90_to_135 = (angle - 90) / 45.0
            left_speed_percentage = 1 - percentage_from_90_to_135

            # right motor stays at 1
            right_speed_percentage = 1

        elif 135 < angle <= 180:
            # left motor transitions from 0 to -1
            percentage_from_135_to_180 = (angle - 135) / 45.0
            left_speed_percentage = -1 * percentage_from_135_to_180

            # right motor stays at 1
            right_speed_percentage = 1

        elif 180 < angle <= 225:
            # left motor transitions from -1 to 0
            percentage_from_180_to_225 = (angle - 180) / 45.0
            left_speed_percentage = -1 + percentage_from_180_to_225

            # right motor transitions from 1 to 0 between 180 and 202.5
            if angle < 202.5:
                percentage_from_180_to_202 = (angle - 180) / 22.5
                right_speed_percentage = 1 - percentage_from_180_to_202

            # right motor is 0 at 202.5
            elif angle == 202.5:
                right_speed_percentage = 0

            # right motor transitions from 0 to -1 between 202.5 and 225
            else:
                percentage_from_202_to_225 = (angle - 202.5) / 22.5
                right_speed_percentage = -1 * percentage_from_202_to_225

        elif 225 < angle <= 270:
            # left motor transitions from 0 to -1
            percentage_from_225_to_270 = (angle - 225) / 45.0
            left_speed_percentage = -1 * percentage_from_225_to_270

            # right motor stays at -1
            right_speed_percentage = -1

        elif 270 < angle <= 315:
            # left motor stays at -1
            left_speed_percentage = -1

            # right motor transitions from -1 to 0
            percentage_from_270_to_315 = (angle - 270) / 45.0
            right_speed_percentage = -1 + percentage_from_270_to_315

        elif 315 < angle <= 360:
            # left motor transitions from -1 to 0 between 315 and 337.5
            if angle < 337.5:
                percentage_from_315_to_337 = (angle - 315) / 22.5
                left_speed_percentage = (1 - percentage_from_315_to_337) * -1

            # left motor is 0 at 337.5
            elif angle == 337.5:
                left_speed_percentage = 0

            # left motor transitions from 0 to 1 between 337.5 and 360
            elif angle > 337.5:
                percentage_from_337_to_360 = (angle - 337.5) / 22.5
                left_speed_percentage = percentage_from_337_to_360

            # right motor transitions from 0 to -1
            percentage_from_315_to_360 = (angle - 315) / 45.0
            right_speed_percentage = -1 * percentage_from_315_to_360

        else:
            raise Exception(
                f"You created a circle with more than 360 degrees ({angle})...that is quite the trick"
            )

        return (left_speed_percentage * 100, right_speed_percentage * 100)
