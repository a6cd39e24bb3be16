"""The EV3 motor of Pybricks 2.0 (pybricks.ev3devices.Motor) and its Control object.

On a brick, Pybricks runs its own controller (lib/pbio/src/servo.c, control.c, trajectory.c): every move
follows a trapezoid speed profile (accelerate, cruise, decelerate; a triangle when the move is short),
computed in encoder counts, 2 per degree on ev3dev (PBDRV_CONFIG_COUNTER_COUNTS_PER_DEGREE), and the
motor's settings (servo.c, settings_servo_ev3_large / _medium) are in counts too.  Here the simulated
tacho motor runs the moves: each is sent as the ev3dev command that does the same thing, with the
ramp_up_sp / ramp_down_sp that give the firmware's acceleration, so a move lands where the firmware's
lands and takes as long.  Settings, targets and angles are kept in counts and converted with the
firmware's fixed-point arithmetic (libfixmath fix16, lib/pbio/src/math.c), so the numbers a program
reads are the brick's.  Writes are cached: an attribute is written only when its value changes.
"""

from errno import EOPNOTSUPP, EPERM

from . import _device, _link
from ._arguments import get_int
from .parameters import Direction, Stop

# -------------------------------------------------------------- fixed point (libfixmath fix16, Q16.16)
FIX16_ONE = 1 << 16
FOUR_DIV_PI = 0x145F3  # libfixmath's FOUR_DIV_PI, used by drivebase.c
COUNTS_PER_DEGREE = 2  # lib/pbio/platform/ev3dev_stretch/pbdrvconfig.h
US_PER_MS = 1000
MS_PER_SECOND = 1000
DURATION_FOREVER = -1
DURATION_MAX_S = 30 * 60  # trajectory.h


def cdiv(a: int, b: int) -> int:
    """C's integer division: truncated toward zero."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def fix16_mul(a: int, b: int) -> int:
    product = a * b
    if product < 0:
        product -= 1
    return (product >> 16) + ((product & 0x8000) >> 15)


def fix16_div(a: int, b: int) -> int:
    """fix16_div with rounding: |a| / |b| rounded half up, then the sign."""
    q = (2 * abs(a) * FIX16_ONE + abs(b)) // (2 * abs(b))
    return q if (a >= 0) == (b >= 0) else -q


def fix16_from(value) -> int:
    """pb_obj_get_fix16: an int exactly, a float rounded to the nearest 1/65536."""
    if isinstance(value, float):
        temp = value * FIX16_ONE
        return int(temp + (0.5 if temp >= 0 else -0.5))
    return get_int(value) * FIX16_ONE


def mul_i32_fix16(a: int, b: int) -> int:
    """pbio_math_mul_i32_fix16."""
    product = a * b
    if product < 0:
        product -= 1
    return (product >> 16) + ((product & 0x8000) >> 15)


def div_i32_fix16(a: int, b: int) -> int:
    """pbio_math_div_i32_fix16."""
    if b == FIX16_ONE:
        return a
    return mul_i32_fix16(a, fix16_div(FIX16_ONE, b))


def isqrt(n: int) -> int:
    """pbio_math_sqrt."""
    if n <= 0:
        return 0
    x0 = n
    while True:
        x1 = (x0 + n // x0) // 2
        if x1 == x0 or x1 == x0 + 1:
            return x0
        x0 = x1


def perm_error():
    """PBIO_ERROR_INVALID_OP as pb_assert raises it (py/pberror.c)."""
    return OSError(EPERM, "EPERM: the motor is in use by a DriveBase, or its control is busy")


# ---------------------------------------------------------------- the trajectory (trajectory.c)
def _timest(b, t):
    return cdiv(b * cdiv(t, US_PER_MS), MS_PER_SECOND)


def _wdiva(w, a):
    return cdiv(w * US_PER_MS, a) * MS_PER_SECOND


def time_based(duration_us, w0, wt, wmax, a, amax):
    """pbio_trajectory_make_time_based, relative to t0 = 0 and th0 = 0: (t1, t2, t3, w1) in us and
    counts/s, the speeds signed.  ValueError / RuntimeError as pb_assert raises the firmware's errors."""
    t3 = 60 * 1000 * 1000 if duration_us == DURATION_FOREVER else duration_us
    if t3 < 0:
        raise ValueError("Invalid argument")
    backward = wt < 0
    if backward:
        wt, w0 = -wt, -w0
    a = min(a, amax)
    abs_max = min(wmax, _timest(a, t3))
    w0 = max(-abs_max, min(w0, abs_max))
    wt = max(-abs_max, min(wt, abs_max))
    if w0 < wt:
        if _wdiva(wt - w0, a) - cdiv(t3 - _wdiva(w0, a), 2) < 0:
            t1, w1 = _wdiva(wt - w0, a), wt
        else:
            t1, w1 = cdiv(t3 - _wdiva(w0, a), 2), cdiv(_timest(a, t3), 2) + cdiv(w0, 2)
    elif w0 > wt:
        t1, w1 = _wdiva(w0 - wt, a), wt
    else:
        t1, w1 = 0, wt
    t3mt2 = _wdiva(w1, a)
    t2mt1 = t3 - t3mt2 - t1
    if t1 < 0 or t2mt1 < 0 or t3mt2 < 0:
        raise RuntimeError("the firmware cannot make this maneuver")
    sign = -1 if backward else 1
    return t1, t1 + t2mt1, t3, sign * w1


def angle_based(th0, th3, w0, wt, wmax, a, amax):
    """pbio_trajectory_make_angle_based, relative to t0 = 0: (t1, t2, t3, th1, th2, w1), in us,
    counts and counts/s, signed as the move goes."""
    if wt == 0:
        raise ValueError("Invalid argument")
    if abs(cdiv(th3 - th0, wt)) + 1 > DURATION_MAX_S:
        raise ValueError("Invalid argument")
    if th3 == th0:
        return 0, 0, 0, th0, th0, 0
    backward = th3 < th0
    if backward:
        th3, w0 = 2 * th0 - th3, -w0
    a = min(a, amax)
    wt = min(abs(wt), wmax)
    w0 = max(-wmax, min(w0, wmax))
    if w0 > 0 and cdiv(w0 * w0, 2 * a) > th3 - th0:
        w0 = isqrt(2 * a * (th3 - th0))
    if w0 < wt:
        a0 = a
        thf = th0 - cdiv(w0 * w0, 2 * a)
        if th3 - thf >= cdiv(wt * wt, a):
            th1, th2, w1 = thf + cdiv(wt * wt, 2 * a), th3 - cdiv(wt * wt, 2 * a), wt
        else:
            th1 = cdiv(th3 + thf, 2)
            th2, w1 = th1, isqrt(2 * a * (th1 - thf))
    else:
        a0 = -a
        th1, th2, w1 = th0 + cdiv(w0 * w0 - wt * wt, 2 * a), th3 - cdiv(wt * wt, 2 * a), wt
    t1 = _wdiva(w1 - w0, a0)
    t2 = t1 + (0 if th2 == th1 else _wdiva(th2 - th1, w1))
    t3 = t2 + _wdiva(w1, a)
    if backward:
        th1, th2, w1 = 2 * th0 - th1, 2 * th0 - th2, -w1
    return t1, t2, t3, th1, th2, w1


# ---------------------------------------------------------------- settings (servo.c)
# name: (max_rate, abs_acceleration, rate_tolerance, count_tolerance, stall_rate_limit, stall_time_us,
#        pid_kp, pid_ki, pid_kd, integral_range, integral_rate, max_control, control_offset)
SETTINGS = {
    "lego-ev3-l-motor": (1600, 3200, 100, 10, 30, 200000, 400, 1200, 5, 45, 10, 10000, 0),
    "lego-ev3-m-motor": (2000, 8000, 100, 10, 30, 200000, 300, 400, 3, 45, 10, 10000, 2000),
}
ACTUATION_SCALE = 100
DRIVERS = tuple(SETTINGS)


class ControlSettings:
    """pbio_control_settings_t: the limits, tolerances and gains of one controller, in counts."""

    def __init__(self, values, counts_per_unit: int):
        (
            self.max_rate,
            self.abs_acceleration,
            self.rate_tolerance,
            self.count_tolerance,
            self.stall_rate_limit,
            self.stall_time,
            self.pid_kp,
            self.pid_ki,
            self.pid_kd,
            self.integral_range,
            self.integral_rate,
            self.max_control,
            self.control_offset,
        ) = values
        self.actuation_scale = ACTUATION_SCALE
        self.counts_per_unit = counts_per_unit

    def to_user(self, counts: int) -> int:
        return div_i32_fix16(counts, self.counts_per_unit)

    def to_counts(self, user: int) -> int:
        return mul_i32_fix16(user, self.counts_per_unit)


class Control:
    """The `control` attribute of a Motor, and DriveBase's heading_control and distance_control
    (extmod/modbuiltins.c, builtins_Control): the controller's settings, read with no arguments and set
    with some; setting them while the controller is busy raises OSError EPERM (raise_if_control_busy)."""

    def __init__(self, settings: ControlSettings, owner):
        self.settings = settings
        self._owner = owner  # answers _busy(), _done(), _stalled(), _trajectory()
        self.scale = settings.counts_per_unit / FIX16_ONE

    def _check_idle(self):
        if self._owner._busy(self):
            raise perm_error()

    def limits(self, speed=None, acceleration=None, actuation=None):
        """(speed deg/s, acceleration deg/s/s, actuation %) or set them (control.c
        pbio_control_settings_get_limits / set_limits)."""
        s = self.settings
        now = (s.to_user(s.max_rate), s.to_user(s.abs_acceleration), s.max_control // s.actuation_scale)
        if speed is None and acceleration is None and actuation is None:
            return now
        self._check_idle()
        speed = now[0] if speed is None else get_int(speed)
        acceleration = now[1] if acceleration is None else get_int(acceleration)
        actuation = now[2] if actuation is None else get_int(actuation)
        if speed < 1 or acceleration < 1 or actuation < 1:
            raise ValueError("Invalid argument")
        if actuation * s.actuation_scale <= s.control_offset:
            raise perm_error()
        s.max_rate = s.to_counts(speed)
        s.abs_acceleration = s.to_counts(acceleration)
        s.max_control = actuation * s.actuation_scale
        return None

    def pid(self, kp=None, ki=None, kd=None, integral_range=None, integral_rate=None, feed_forward=None):
        """(kp, ki, kd, integral_range, integral_rate, feed_forward) or set them (control.c
        pbio_control_settings_get_pid / set_pid).  Kept and returned; the simulated motor's own
        controller does the work, so they do not change how it moves."""
        s = self.settings
        now = (
            s.pid_kp,
            s.pid_ki,
            s.pid_kd,
            s.to_user(s.integral_range),
            s.to_user(s.integral_rate),
            s.control_offset // s.actuation_scale,
        )
        given = (kp, ki, kd, integral_range, integral_rate, feed_forward)
        if all(value is None for value in given):
            return now
        self._check_idle()
        kp, ki, kd, i_range, i_rate, offset = (
            old if new is None else get_int(new) for new, old in zip(given, now, strict=False)
        )
        if min(kp, ki, kd, i_range, i_rate, offset) < 0:
            raise ValueError("Invalid argument")
        if offset * s.actuation_scale >= s.max_control:
            raise perm_error()
        s.pid_kp, s.pid_ki, s.pid_kd = kp, ki, kd
        s.integral_range, s.integral_rate = s.to_counts(i_range), s.to_counts(i_rate)
        s.control_offset = offset * s.actuation_scale
        return None

    def target_tolerances(self, speed=None, position=None):
        """(speed, position) or set them (control.c pbio_control_settings_*_target_tolerances)."""
        s = self.settings
        now = (s.to_user(s.rate_tolerance), s.to_user(s.count_tolerance))
        if speed is None and position is None:
            return now
        self._check_idle()
        speed = now[0] if speed is None else get_int(speed)
        position = now[1] if position is None else get_int(position)
        if position < 0 or speed < 0:
            raise ValueError("Invalid argument")
        s.count_tolerance, s.rate_tolerance = s.to_counts(position), s.to_counts(speed)
        return None

    def stall_tolerances(self, speed=None, time=None):
        """(speed deg/s, time ms) or set them (control.c pbio_control_settings_*_stall_tolerances)."""
        s = self.settings
        now = (s.to_user(s.stall_rate_limit), s.stall_time // US_PER_MS)
        if speed is None and time is None:
            return now
        self._check_idle()
        speed = now[0] if speed is None else get_int(speed)
        time = now[1] if time is None else get_int(time)
        if speed < 0 or time < 0:
            raise ValueError("Invalid argument")
        s.stall_rate_limit, s.stall_time = s.to_counts(speed), time * US_PER_MS
        return None

    def trajectory(self):
        """The active maneuver as (t0, t1, t2, t3 in ms, th0..th3 in counts, w0, w1, a0, a2), or None
        when the controller is passive (builtins_Control_trajectory)."""
        return self._owner._trajectory(self)

    def done(self) -> bool:
        """pbio_control_is_done: passive, or on target."""
        return self._owner._done(self)

    def stalled(self) -> bool:
        """pbio_control_is_stalled: active and stalled."""
        return self._owner._stalled(self)


STOP_ACTIONS = {Stop.COAST: "coast", Stop.BRAKE: "brake", Stop.HOLD: "hold"}


def stop_action(then) -> str:
    try:
        return STOP_ACTIONS[then]
    except (KeyError, TypeError):
        raise TypeError("then must be a Stop, e.g. Stop.HOLD") from None


# control types (pbio_control_type_t)
PASSIVE, TIMED, ANGLE = None, "timed", "angle"


class Motor:
    """LEGO MINDSTORMS EV3 Medium or Large Motor (pybricks.ev3devices.Motor, Pybricks 2.0)."""

    def __init__(self, port, positive_direction=Direction.CLOCKWISE, gears=None):
        """extmod/modmotor.c motor_Motor_make_new and servo.c pbio_servo_setup: find the motor, coast
        it, and count the angle from 0 here (ev3dev has no absolute count)."""
        if positive_direction is Direction.CLOCKWISE:
            sign = 1
        elif positive_direction is Direction.COUNTERCLOCKWISE:
            sign = -1
        else:
            raise TypeError("positive_direction must be a Direction")
        gear_ratio = FIX16_ONE
        if gears is not None:
            trains = list(gears)
            if isinstance(trains[0], int) and isinstance(trains[-1], int):
                trains = [trains]
            for train in trains:
                first, last = get_int(list(train)[0]), get_int(list(train)[-1])
                if first < 1 or last < 1:
                    raise ValueError("Invalid argument")
                gear_ratio = fix16_div(fix16_mul(gear_ratio, last * FIX16_ONE), first * FIX16_ONE)
        self._port = port
        self._name = _device.find(port, "tacho-motor", DRIVERS, motor=True)
        for other in _CLAIMED:
            if other._name == self._name and other._claimed:
                raise perm_error()  # pbio_servo_setup: "already in use by higher level entity"
        driver = _link.read("tacho-motor", self._name, "driver_name")
        self._max_speed = int(_link.read("tacho-motor", self._name, "max_speed"))
        self._sign = sign
        self._counts_per_unit = fix16_mul(COUNTS_PER_DEGREE * FIX16_ONE, gear_ratio)
        self._settings = ControlSettings(SETTINGS[driver], self._counts_per_unit)
        self.control = Control(self._settings, self)
        self._written = {}
        self._claimed = False
        self._type = PASSIVE
        self._forever = False
        self._after = Stop.COAST
        self._target = 0  # angle control: the target count
        self._traj = None  # (t0, t1, t2, t3, th0, th1, th2, th3, w0, w1, a0, a2) of the last maneuver
        self._halt("coast")
        self._offset = 0
        self._offset = self._count()  # pbio_tacho_reset_count(tacho, 0)

    def __repr__(self):
        direction = "clockwise" if self._sign == 1 else "counterclockwise"
        return f"Motor properties:\n------------------------\nPort\t\t {self._port.name[-1]}\nPositive dir.\t {direction}"

    # ------------------------------------------------------------ the device
    def _write(self, attribute: str, value: str) -> None:
        if self._written.get(attribute) != value:
            _link.write("tacho-motor", self._name, attribute, value)
            self._written[attribute] = value

    def _command(self, command: str) -> None:
        _link.write("tacho-motor", self._name, "command", command)
        self._written["command"] = command

    def _count(self) -> int:
        """pbio_tacho_get_count: counts, in this motor's positive direction, from its last reset."""
        return (
            self._sign * COUNTS_PER_DEGREE * int(_link.read("tacho-motor", self._name, "position"))
            - self._offset
        )

    def _rate(self) -> int:
        return self._sign * COUNTS_PER_DEGREE * int(_link.read("tacho-motor", self._name, "speed"))

    def _device_speed(self, rate: int) -> str:
        """A speed in counts/s as the device's speed_sp (deg/s of the shaft, within its max_speed)."""
        dps = cdiv(self._sign * rate, COUNTS_PER_DEGREE)
        return str(max(-self._max_speed, min(dps, self._max_speed)))

    def _ramp(self, acceleration: int) -> str:
        """The ramp_*_sp that gives `acceleration` counts/s/s (ms from 0 to max_speed), rounded."""
        ms = (self._max_speed * COUNTS_PER_DEGREE * 2000 // max(acceleration, 1) + 1) // 2
        return str(max(1, min(ms, 60000)))

    def _ramps(self, acceleration: int) -> None:
        ramp = self._ramp(acceleration)
        self._write("ramp_up_sp", ramp)
        self._write("ramp_down_sp", ramp)

    def _halt(self, action: str) -> None:
        """Stop at once (the firmware coasts, brakes or holds in its next control step)."""
        self._write("ramp_down_sp", "0")
        self._write("stop_action", action)
        self._command("stop")

    def _go_forever(self, rate: int, acceleration: int, send: bool = True) -> str:
        """Run at `rate` counts/s.  With send=False the setpoints are written and the command is
        returned, for a drive base to start both wheels at the same moment."""
        speed, ramp, written = self._device_speed(rate), self._ramp(acceleration), self._written
        if written.get("command") == "run-forever" and written.get("speed_sp") == speed:
            if written.get("ramp_up_sp") == ramp == written.get("ramp_down_sp"):
                return ""  # already running so: the firmware's patched trajectory is the same one
        self._write("ramp_up_sp", ramp)
        self._write("ramp_down_sp", ramp)
        self._write("speed_sp", speed)
        return self._send("run-forever", send)

    def _send(self, command: str, send: bool) -> str:
        if send:
            self._command(command)
            return ""
        self._written["command"] = command
        return command

    def _go_to(self, target: int, rate: int, acceleration: int, action: str, send: bool = True) -> str:
        position = (self._sign * (target + self._offset)) / COUNTS_PER_DEGREE
        self._write("position_sp", str(int(round(position))))
        self._write("speed_sp", self._device_speed(abs(rate)).lstrip("-"))
        self._ramps(acceleration)
        self._write("stop_action", action)
        return self._send("run-to-abs-pos", send)

    def _go_timed(self, rate: int, time_ms: int, acceleration: int, action: str) -> None:
        self._write("speed_sp", self._device_speed(rate))
        self._write("time_sp", str(time_ms))
        self._ramps(acceleration)
        self._write("stop_action", action)
        self._command("run-timed")

    def _running(self) -> bool:
        return "running" in _link.read("tacho-motor", self._name, "state")

    def _wait(self) -> None:
        """wait_for_completion: until the maneuver is done (the firmware checks every 5 ms)."""
        while not self._done(self.control):
            _link.poll("tacho-motor", self._name, "state", 100)

    # ------------------------------------------------------------ what Control asks
    def _busy(self, control) -> bool:
        self._done(control)
        return self._type is not PASSIVE

    def _done(self, control) -> bool:
        if self._type is PASSIVE:
            return True
        if self._forever:
            return False
        if self._running():
            return False
        if self._after is not Stop.HOLD:
            self._type = PASSIVE  # control.c control_update: on target, then passive
        elif self._type is TIMED:
            self._type = ANGLE  # ... or a hold where the timed maneuver ended
            self._target = self._count()
        return True

    def _stalled(self, control) -> bool:
        if self._type is PASSIVE:
            return False
        return "stalled" in _link.read("tacho-motor", self._name, "state")

    def _trajectory(self, control):
        self._done(control)
        return None if self._type is PASSIVE else self._traj

    def _check_free(self) -> None:
        if self._claimed:
            raise perm_error()

    # ------------------------------------------------------------ DCMotor methods
    def dc(self, duty):
        """Run at a duty cycle in %, without speed control (servo.c pbio_servo_set_duty_cycle)."""
        duty = get_int(duty)
        self._check_free()
        self._type = PASSIVE
        duty = max(-100, min(duty, 100))
        self._write("duty_cycle_sp", str(self._sign * duty))
        if self._written.get("command") != "run-direct":
            self._command("run-direct")

    def stop(self, stop_type=Stop.COAST):
        """Coast (EV3 MicroPython 1.0: stop(Stop.BRAKE) brakes and stop(Stop.HOLD) holds;
        bricks/ev3dev/modules/pybricks/ev3devices.py Motor.stop)."""
        if stop_type is Stop.COAST:
            self._check_free()
            self._type = PASSIVE
            self._halt("coast")
        elif stop_type is Stop.BRAKE:
            self.brake()
        elif stop_type is Stop.HOLD:
            self.hold()
        else:
            raise ValueError("Invalid Argument")

    def brake(self):
        """Stop, the motor's terminals shorted (passive braking)."""
        self._check_free()
        self._type = PASSIVE
        self._halt("brake")

    # ------------------------------------------------------------ Motor methods
    def hold(self):
        """Stop and keep the motor where it is (servo.c pbio_servo_stop with PBIO_ACTUATION_HOLD)."""
        self._check_free()
        self._target = self._count()
        self._type, self._forever, self._after = ANGLE, False, Stop.HOLD
        self._halt("hold")

    def angle(self) -> int:
        """The rotation angle in degrees (tacho.c pbio_tacho_get_angle)."""
        return div_i32_fix16(self._count(), self._counts_per_unit)

    def speed(self) -> int:
        """The speed in deg/s (tacho.c pbio_tacho_get_angular_rate)."""
        return div_i32_fix16(self._rate(), self._counts_per_unit)

    def reset_angle(self, angle=None):
        """Count the angle from `angle` here.  With no angle it would reset to the absolute angle, which
        an EV3 motor does not have: OSError EOPNOTSUPP (servo.c pbio_servo_reset_angle, tacho.c)."""
        self._check_free()
        if angle is None:
            raise OSError(EOPNOTSUPP, "EOPNOTSUPP: an EV3 motor has no absolute angle; give one")
        counts = mul_i32_fix16(get_int(angle), self._counts_per_unit)
        busy = self._busy(self.control)
        old = self._count()
        reference = old if self._running() or not busy else self._target
        self._offset += old - counts
        if busy:  # "make it stop and hold right here right now", the old target kept relative
            self._track(counts + reference - old)

    def run(self, speed):
        """Run at `speed` deg/s until told otherwise, accelerating as the control limits say."""
        rate = self._settings.to_counts(get_int(speed))
        self._check_free()
        s = self._settings
        rate = max(-s.max_rate, min(rate, s.max_rate))
        self._type, self._forever, self._after = TIMED, True, Stop.COAST
        self._go_forever(rate, s.abs_acceleration)

    def run_time(self, speed, time, then=Stop.HOLD, wait=True):
        """Run at `speed` for `time` ms, accelerating and then slowing down so as to stand still at the
        end (servo.c pbio_servo_run_time, trajectory.c pbio_trajectory_make_time_based)."""
        rate = self._settings.to_counts(get_int(speed))
        time = get_int(time)
        if time < 0 or time > DURATION_MAX_S * MS_PER_SECOND:
            raise ValueError("Invalid argument")
        action = stop_action(then)
        self._check_free()
        s = self._settings
        w0 = self._rate()
        t1, t2, t3, w1 = time_based(
            time * US_PER_MS, w0, rate, s.max_rate, s.abs_acceleration, s.abs_acceleration
        )
        a = s.abs_acceleration
        th0 = self._count()
        self._traj = (0, t1 // 1000, t2 // 1000, t3 // 1000, th0, th0, th0, th0, w0, w1, a, -a)
        self._type, self._forever, self._after = TIMED, False, then
        self._go_timed(w1, t2 // US_PER_MS, s.abs_acceleration, action)
        if wait:
            self._wait()

    def run_until_stalled(self, speed, then=Stop.COAST, duty_limit=None):
        """Run at `speed` until the motor stalls, then stop with `then`; returns the angle there
        (modmotor.c motor_Motor_run_until_stalled: it always waits)."""
        rate = self._settings.to_counts(get_int(speed))
        action = stop_action(then)
        if duty_limit is not None:
            get_int(duty_limit)
        self._check_free()
        s = self._settings
        rate = max(-s.max_rate, min(rate, s.max_rate))
        self._type, self._forever, self._after = TIMED, True, then
        self._go_forever(rate, s.abs_acceleration)
        while "stalled" not in _link.read("tacho-motor", self._name, "state"):
            _link.poll("tacho-motor", self._name, "state", 100)
        self._forever = False
        if then is Stop.HOLD:
            self._type, self._target = ANGLE, self._count()
        else:
            self._type = PASSIVE
        self._halt(action)
        return self.angle()

    def run_angle(self, speed, rotation_angle, then=Stop.HOLD, wait=True):
        """Turn `rotation_angle` degrees at `speed`; a negative speed turns the other way, so both
        negative turn forward (control.c pbio_control_start_relative_angle_control)."""
        rate = self._settings.to_counts(get_int(speed))
        relative = self._settings.to_counts(get_int(rotation_angle))
        action = stop_action(then)
        self._check_free()
        start = self._start_count()
        target = start + (-relative if rate < 0 else relative)
        if target == start:  # pbio_control_start_hold_control: no error even at speed 0
            self._target = target
            self._type, self._forever, self._after = ANGLE, False, Stop.HOLD
            self._halt("hold")
            return
        self._run_to(rate, target, then, action, wait, start)

    def run_target(self, speed, target_angle, then=Stop.HOLD, wait=True):
        """Turn to `target_angle` at `speed` (its sign does not matter; pbio_servo_run_target)."""
        rate = self._settings.to_counts(get_int(speed))
        target = self._settings.to_counts(get_int(target_angle))
        action = stop_action(then)
        self._check_free()
        self._run_to(rate, target, then, action, wait, self._start_count())

    def _start_count(self) -> int:
        """Where a relative move counts from: the physical count when passive, else the reference
        (the held target, once a maneuver is done)."""
        if self._type is not PASSIVE and self._done(self.control) and self._type is ANGLE:
            return self._target
        return self._count()

    def _run_to(self, rate, target, then, action, wait, start):
        s = self._settings
        w0 = self._rate()
        t1, t2, t3, th1, th2, w1 = angle_based(
            start, target, w0, rate, s.max_rate, s.abs_acceleration, s.abs_acceleration
        )
        a = s.abs_acceleration if target >= start else -s.abs_acceleration
        self._traj = (0, t1 // 1000, t2 // 1000, t3 // 1000, start, th1, th2, target, w0, w1, a, -a)
        self._target = target
        self._type, self._forever, self._after = ANGLE, False, then
        self._go_to(target, min(abs(rate), s.max_rate), s.abs_acceleration, action)
        if wait:
            self._wait()

    def track_target(self, target_angle):
        """Follow a target that changes all the time: hold control at once at the new target, with no
        profile (servo.c pbio_servo_track_target)."""
        target = self._settings.to_counts(get_int(target_angle))
        self._check_free()
        self._track(target)

    def _track(self, target: int) -> None:
        """pbio_control_start_hold_control at `target`: the shaft is pulled there at full speed."""
        self._target = target
        self._type, self._forever, self._after = ANGLE, False, Stop.HOLD
        self._write("ramp_down_sp", "0")
        self._write("ramp_up_sp", "0")
        position = (self._sign * (target + self._offset)) / COUNTS_PER_DEGREE
        self._write("position_sp", str(int(round(position))))
        self._write("speed_sp", str(self._max_speed))
        self._write("stop_action", "hold")
        self._command("run-to-abs-pos")

    # ------------------------------------------------------------ EV3 MicroPython 1.0
    def stalled(self) -> bool:
        """1.0: whether the motor is stalled (ev3devices.py: self.control.stalled())."""
        return self.control.stalled()

    def set_dc_settings(self, duty_limit, duty_offset):
        """1.0 (ev3devices.py): control.limits(actuation=duty_limit); control.pid(feed_forward=...)."""
        self.control.limits(actuation=duty_limit)
        self.control.pid(feed_forward=duty_offset)

    def set_run_settings(self, max_speed, acceleration):
        """1.0 (ev3devices.py): control.limits(max_speed, acceleration)."""
        self.control.limits(max_speed, acceleration)

    def set_pid_settings(
        self, kp, ki, kd, tight_loop_limit, angle_tolerance, speed_tolerance, stall_speed, stall_time
    ):
        """1.0 (ev3devices.py): control.pid, target_tolerances and stall_tolerances."""
        self.control.pid(kp, ki, kd)
        self.control.target_tolerances(speed_tolerance, angle_tolerance)
        self.control.stall_tolerances(stall_speed, stall_time)


_CLAIMED = []  # the motors the drive base holds (the firmware's one drive base: motorpoll.c)


class DCMotor:
    """A motor driven by duty cycle only, without its encoder (pybricks.iodevices.DCMotor; extmod/modmotor.c
    motor_DCMotor_type): on an EV3 any motor on an output port, here one of the robot's EV3 motors."""

    def __init__(self, port, positive_direction=Direction.CLOCKWISE):
        """modmotor.c motor_DCMotor_make_new: find the motor (pbio_dcmotor_get), and coast it."""
        if positive_direction is Direction.CLOCKWISE:
            self._sign = 1
        elif positive_direction is Direction.COUNTERCLOCKWISE:
            self._sign = -1
        else:
            raise TypeError("positive_direction must be a Direction")
        self._port = port
        self._name = _device.find(port, "tacho-motor", DRIVERS, motor=True)
        self._direct = False
        self.stop()

    def __repr__(self):
        direction = "clockwise" if self._sign == 1 else "counterclockwise"
        return f"Motor properties:\n------------------------\nPort\t\t {self._port.name[-1]}\nPositive dir.\t {direction}"

    def dc(self, duty):
        """Run at `duty` % (-100..100) of the battery's voltage (pbio_dcmotor_set_duty_cycle_usr)."""
        duty = max(-100, min(get_int(duty), 100))
        _link.write("tacho-motor", self._name, "duty_cycle_sp", str(self._sign * duty))
        if not self._direct:
            _link.write("tacho-motor", self._name, "command", "run-direct")
            self._direct = True

    def stop(self):
        """Coast: the motor rolls out freely (pbio_dcmotor_coast)."""
        self._halt("coast")

    def brake(self):
        """Brake passively: the motor's terminals shorted (pbio_dcmotor_brake)."""
        self._halt("brake")

    def _halt(self, action: str) -> None:
        _link.write("tacho-motor", self._name, "stop_action", action)
        _link.write("tacho-motor", self._name, "command", "stop")
        self._direct = False
