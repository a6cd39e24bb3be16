"""Robotics: the DriveBase of Pybricks 2.0 (pybricks.robotics), with EV3 MicroPython 1.0's stop(Stop.X)
and drive_time (bricks/ev3dev/modules/pybricks/robotics.py).

On a brick the drive base controls the sum and the difference of its two motors' counts (distance and
heading, lib/pbio/src/drivebase.c), each with the firmware's trapezoid profile.  A straight move keeps
the difference and a turn the sum, so here each is sent to the two wheels' motors as the same
profile, halved: a run to a position with the ramps that give the firmware's acceleration.  Units are
mm, mm/s, deg and deg/s; a positive turn is clockwise (to the right, seen from above).
"""

import time as _time

from . import _link
from ._arguments import get_int
from ._motor import (
    _CLAIMED,
    ANGLE,
    FIX16_ONE,
    FOUR_DIV_PI,
    PASSIVE,
    TIMED,
    Control,
    ControlSettings,
    Motor,
    angle_based,
    fix16_div,
    fix16_from,
    fix16_mul,
    perm_error,
)
from .parameters import Stop

__all__ = ["DriveBase"]


def _adopt(left: ControlSettings, right: ControlSettings) -> tuple:
    """drivebase.c drivebase_adopt_settings: the distance (and, alike, heading) controller's settings
    from the two motors'."""
    if left.actuation_scale != right.actuation_scale or left.control_offset != right.control_offset:
        raise ValueError("Invalid argument")  # e.g. a Large and a Medium motor
    return (
        left.max_rate + right.max_rate,
        (left.abs_acceleration + right.abs_acceleration) * 2,
        left.rate_tolerance + right.rate_tolerance,
        left.count_tolerance + right.count_tolerance,
        left.stall_rate_limit + right.stall_rate_limit,
        min(left.stall_time, right.stall_time),
        (left.pid_kp + right.pid_kp) // 4,
        (left.pid_ki + right.pid_ki) // 4,
        (left.pid_kd + right.pid_kd) // 4,
        left.integral_range + right.integral_range,
        left.integral_rate + right.integral_rate,
        min(left.max_control, right.max_control),
        left.control_offset,
    )


_WRITE_US = 3_000  # what a write costs on the simulated brick (ev3sim2d/brick/link.py WRITE_US)
_active = []  # the drive base whose motors are claimed: the firmware has one (motorpoll.c)


class DriveBase:
    """A robotic vehicle with two powered wheels and an optional support wheel or caster."""

    def __init__(self, left_motor, right_motor, wheel_diameter, axle_track):
        """robotics_DriveBase_make_new and drivebase.c pbio_drivebase_setup."""
        for motor in (left_motor, right_motor):
            if not isinstance(motor, Motor):
                raise TypeError(f"can't convert {type(motor).__name__} to Motor")
        if left_motor._name == right_motor._name:
            raise ValueError("Invalid argument")
        for old in _active:  # pbio_drivebase_stop_force: the earlier drive base lets its motors go
            old._release()
            old.left._halt("coast")
            old.right._halt("coast")
        _active.clear()
        left_motor.stop()
        right_motor.stop()
        diameter, track = fix16_from(wheel_diameter), fix16_from(axle_track)
        if diameter <= 0 or track <= 0:
            raise ValueError("Invalid argument")
        cpu = left_motor._counts_per_unit
        if cpu != right_motor._counts_per_unit:
            raise ValueError("Invalid argument")
        self.left, self.right = left_motor, right_motor
        values = _adopt(left_motor._settings, right_motor._settings)
        heading_cpu = fix16_mul(cpu, fix16_div(fix16_mul(track, 2 * FIX16_ONE), diameter))
        distance_cpu = fix16_mul(cpu, fix16_div(fix16_mul(180 * FIX16_ONE, FOUR_DIV_PI), diameter))
        self._heading = ControlSettings(values, heading_cpu)
        self._distance = ControlSettings(values, distance_cpu)
        self.heading_control = Control(self._heading, self)
        self.distance_control = Control(self._distance, self)
        self._type = PASSIVE
        self._targets = (0, 0)  # while holding: the two wheels' targets, counts
        self._traj = None
        self._sum_offset = self._dif_offset = 0
        sd, sh = self._distance, self._heading
        self._straight_speed = sd.to_user(sd.max_rate) // 3
        self._straight_acceleration = sd.to_user(sd.abs_acceleration) // 3
        self._turn_rate = sh.to_user(sh.max_rate) // 3
        self._turn_acceleration = sh.to_user(sh.abs_acceleration) // 3

    # ------------------------------------------------------------ claims and state
    def _claim(self) -> None:
        """pbio_drivebase_claim_servos(db, true): the motors' own control stops and they refuse
        commands (OSError EPERM) until the drive base stops."""
        for motor in (self.left, self.right):
            motor._claimed = True
            motor._type = PASSIVE
            if motor not in _CLAIMED:
                _CLAIMED.append(motor)
        if self not in _active:
            _active.append(self)

    def _release(self) -> None:
        for motor in (self.left, self.right):
            motor._claimed = False
            motor._type = PASSIVE
            if motor in _CLAIMED:
                _CLAIMED.remove(motor)
        self._type = PASSIVE

    def _busy(self, control) -> bool:
        return self._type is not PASSIVE

    def _done(self, control) -> bool:
        if self._type is not ANGLE:
            return self._type is PASSIVE
        return not (self.left._running() or self.right._running())

    def _stalled(self, control) -> bool:
        if self._type is PASSIVE:
            return False
        return self.left._stalled(None) or self.right._stalled(None)

    def _trajectory(self, control):
        return None if self._type is PASSIVE else self._traj

    def _counts(self) -> tuple:
        return self.left._count(), self.right._count()

    def _wait(self) -> None:
        """wait_for_completion_drivebase: until both controllers are on target."""
        for motor in (self.left, self.right):
            while motor._running():
                _link.poll("tacho-motor", motor._name, "state", 100)

    # ------------------------------------------------------------ moves
    def _start(self) -> tuple:
        """Where a maneuver starts: the held targets when holding, else the wheels' counts."""
        return self._targets if self._type is ANGLE else self._counts()

    def _move(self, settings, relative: int, rate: int, acceleration: int, turning: bool) -> None:
        """drivebase.c pbio_drivebase_straight / _turn: one controller moves `relative` counts, the other
        holds; as the wheels see it, each turns half of it, the same way (sum) or opposite ways (dif)."""
        self._claim()
        left0, right0 = self._start()
        start = left0 - right0 if turning else left0 + right0
        if relative:
            t1, t2, t3, th1, th2, w1 = angle_based(
                start, start + relative, 0, rate, settings.max_rate, acceleration, settings.abs_acceleration
            )
            self._traj = (0, t1 // 1000, t2 // 1000, t3 // 1000, start, th1, th2, start + relative, 0, w1)
        half = relative / 2
        targets = (left0 + half, right0 - half) if turning else (left0 + half, right0 + half)
        self._targets = targets
        self._type = ANGLE
        wheel_rate = min(abs(rate), settings.max_rate) / 2
        wheel_acceleration = min(acceleration, settings.abs_acceleration) / 2
        if relative:
            commands = [
                motor._go_to(target, int(wheel_rate), int(wheel_acceleration), "hold", send=False)
                for motor, target in zip((self.left, self.right), targets, strict=False)
            ]
            self._start_both(commands)
        else:
            self.left._halt("hold")
            self.right._halt("hold")
        self._wait()

    def _start_both(self, commands) -> None:
        """Both wheels' commands back to back, their setpoints written before: on a brick one control
        step starts both.  The simulated world takes in writes tick by tick, so when the two would fall
        into different ticks the program first waits for the next tick (at most one write's time)."""
        if all(commands):
            tick_us = _link.tick_us()
            into_tick_us = round(_time.time() * 1_000_000) % tick_us
            if into_tick_us + _WRITE_US >= tick_us:
                _time.sleep((tick_us - into_tick_us) / 1_000_000)
        for motor, command in zip((self.left, self.right), commands, strict=False):
            if command:
                _link.write("tacho-motor", motor._name, "command", command)

    def straight(self, distance):
        """Drive `distance` mm (backwards when negative) and hold there; blocks until done."""
        sd = self._distance
        relative = sd.to_counts(get_int(distance))
        self._move(
            sd, relative, sd.to_counts(self._straight_speed), sd.to_counts(self._straight_acceleration), False
        )

    def turn(self, angle):
        """Turn in place `angle` degrees, clockwise when positive, and hold there; blocks until done."""
        sh = self._heading
        relative = sh.to_counts(get_int(angle))
        self._move(sh, relative, sh.to_counts(self._turn_rate), sh.to_counts(self._turn_acceleration), True)

    def drive(self, speed, turn_rate):
        """Start driving at `speed` mm/s, turning at `turn_rate` deg/s (clockwise positive); returns at once.
        Each is limited to the control limits and reached at the limits' acceleration
        (drivebase.c pbio_drivebase_drive)."""
        sd, sh = self._distance, self._heading
        total = max(-sd.max_rate, min(sd.to_counts(get_int(speed)), sd.max_rate))
        difference = max(-sh.max_rate, min(sh.to_counts(get_int(turn_rate)), sh.max_rate))
        if self._type is not TIMED:
            self._claim()
            self._type = TIMED
            self._traj = None
        acceleration = sd.abs_acceleration // 2
        self._start_both(
            (
                self.left._go_forever((total + difference) // 2, acceleration, send=False),
                self.right._go_forever((total - difference) // 2, acceleration, send=False),
            )
        )

    def stop(self, stop_type=Stop.COAST):
        """Stop, the motors coasting, and let them go (1.0: Stop.BRAKE brakes them and Stop.HOLD holds
        with straight(0); bricks/ev3dev/modules/pybricks/robotics.py DriveBase.stop)."""
        if stop_type is Stop.COAST:
            self._release()
            self.left._halt("coast")
            self.right._halt("coast")
        elif stop_type is Stop.BRAKE:
            self.stop()
            self.left.brake()
            self.right.brake()
        elif stop_type is Stop.HOLD:
            self.straight(0)
        else:
            raise ValueError("Invalid Argument")

    def drive_time(self, speed, steering, time):
        """1.0: drive(speed, steering), wait `time` ms, stop (robotics.py DriveBase.drive_time)."""
        self.drive(speed, steering)
        _time.sleep(get_int(time) / 1000)
        self.stop()

    # ------------------------------------------------------------ measuring
    def distance(self) -> int:
        """mm driven since the last reset (pbio_drivebase_get_state)."""
        left, right = self._counts()
        return self._distance.to_user(left + right - self._sum_offset)

    def angle(self) -> int:
        """Degrees turned since the last reset, clockwise positive."""
        left, right = self._counts()
        return self._heading.to_user(left - right - self._dif_offset)

    def state(self) -> tuple:
        """(distance mm, drive speed mm/s, angle deg, turn rate deg/s)."""
        left, right = self._counts()
        left_rate, right_rate = self.left._rate(), self.right._rate()
        sd, sh = self._distance, self._heading
        return (
            sd.to_user(left + right - self._sum_offset),
            sd.to_user(left_rate + right_rate),
            sh.to_user(left - right - self._dif_offset),
            sh.to_user(left_rate - right_rate),
        )

    def reset(self) -> None:
        """Distance and angle count from 0 here (pbio_drivebase_reset_state)."""
        left, right = self._counts()
        self._sum_offset, self._dif_offset = left + right, left - right

    def settings(
        self, straight_speed=None, straight_acceleration=None, turn_rate=None, turn_acceleration=None
    ):
        """(straight_speed, straight_acceleration, turn_rate, turn_acceleration), or set some: each is
        made positive and kept within the control limits; OSError EPERM while the drive base is active
        (robotics_DriveBase_settings)."""
        given = (straight_speed, straight_acceleration, turn_rate, turn_acceleration)
        now = (self._straight_speed, self._straight_acceleration, self._turn_rate, self._turn_acceleration)
        if all(value is None for value in given):
            return now
        if self._type is not PASSIVE:
            raise perm_error()
        sd, sh = self._distance, self._heading
        limits = (sd.to_user(sd.max_rate), sd.to_user(sd.abs_acceleration))
        limits += (sh.to_user(sh.max_rate), sh.to_user(sh.abs_acceleration))
        values = [
            min(limit, abs(old if new is None else get_int(new)))
            for new, old, limit in zip(given, now, limits, strict=False)
        ]
        (self._straight_speed, self._straight_acceleration, self._turn_rate, self._turn_acceleration) = values
        return None
