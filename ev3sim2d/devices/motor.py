"""EV3 Large and Medium motors, as the ev3dev tacho-motor driver shows them.

Motors have infinite acceleration unless the program sets ramp_up_sp /
ramp_down_sp: a wheel turns at speed_sp at once and stops at once on brake or
hold; coast lets it roll out with a short time constant.  With ramps the speed
changes linearly (ramp_up_sp ms from 0 to max_speed, ramp_down_sp ms back), as
the driver's ramp does, and `state` says `ramping` meanwhile.
Each tick the motor *plans* how far its shaft should turn; the robot moves,
and the motor is told how far the shaft really turned (`measured`), which is
what the encoder counts.  A shaft that turns much less than planned for a
while (a robot pushing a wall, or a run at speed 0) is `stalled`; while it
lags, the speed PID's error adds up and the duty cycle rises to 100 %, where
the motor is `overloaded`.

Runs end exactly: run-to-*-pos lands on position_sp and run-timed turns for
exactly time_sp, even when that falls between two ticks.

As in the driver, the count and the setpoints are kept in the motor's own frame
and `polarity` only negates position, speed, duty_cycle, position_sp, speed_sp
and duty_cycle_sp as they are read and written (tacho_motor_class.c): inversing
it turns a position of 90 into -90 and leaves the shaft alone.  A run-to-rel-pos
sent when the last command was also run-to-rel-pos counts from that one's target,
not from where the shaft is (tm_send_command).  `reset` coasts the motor to a
stop and counts from 0 from there (legoev3_motor_reset).  Writing position is
accepted at any time, also while the motor runs, and ends a run to a position
where the shaft is (legoev3_motor_set_position).

A motor that drives no wheel (an arm, a gripper, a launcher) turns its shaft as
planned (`turn_free`) unless the robot file gives it an end stop or a load.  At
an end stop (`limits_deg`) the shaft stops dead, as against a hard stop.  A load
(`load_pct`, a torque in % of the motor's stall torque, resisting whichever way
the shaft turns, never turning it by itself) takes that much of the motor's
power, as a DC motor's torque falls linearly with its speed: a regulated run at
full duty reaches (100 - load_pct) % of max_speed, run-direct at duty d turns at
(d - load_pct) % of it, and a coasting shaft stops at once.  Such a motor reports
`stalled` as the driver does: once its speed has been 0 for 100 ms while it runs
(update_stall); and, like the driver, it keeps running then: a run-to-*-pos
that cannot reach position_sp stays `running` (and `overloaded`: its speed PID
drives the duty cycle to 100 %) until the program stops it, while
python-ev3dev2's blocking moves return as soon as `stalled` shows
(wait_until_not_moving).

Driver behaviour mirrored here is from github.com/ev3dev/lego-linux-drivers:
motors/tacho_motor_class.c (commands, ramps, PID attributes), ev3/legoev3_motor.c
(stall, run to position, state), motors/ev3_motor_defs.c (PID defaults).
"""

from __future__ import annotations

import math

from .device import Device, int_rule, invalid, parse_int

# ev3dev tacho-motor figures for the EV3 motors (driver name, max_speed in deg/s, hold_pid/Kp)
KINDS = {
    "large": ("lego-ev3-l-motor", 1050, 80000),
    "medium": ("lego-ev3-m-motor", 1560, 160000),
}
# motors/ev3_motor_defs.c: speed_pid_k {1000, 60, 0} for both, position_pid_k {Kp, 0, 0}
SPEED_PID = {"speed_pid/Kp": 1000, "speed_pid/Ki": 60, "speed_pid/Kd": 0}
COMMANDS = ("run-forever", "run-to-abs-pos", "run-to-rel-pos", "run-timed", "run-direct", "stop", "reset")
STOP_ACTIONS = ("coast", "brake", "hold")

COAST_TIME_CONSTANT_S = 0.08  # how quickly a coasting wheel rolls out
STALL_WINDOW_S = 0.1  # how long a shaft must lag before the motor reports stalled
STALL_RATIO = 0.25  # ... turning less than this share of the planned travel
PID_SCALE = 10000  # tm_pid_update: duty = (Kp*error + Ki*integral + Kd*delta) / 10000

# state bits, also used by the trace
RUNNING, RAMPING, HOLDING, OVERLOADED, STALLED = 1, 2, 4, 8, 16
STATE_NAMES = (
    (RUNNING, "running"),
    (RAMPING, "ramping"),
    (HOLDING, "holding"),
    (OVERLOADED, "overloaded"),
    (STALLED, "stalled"),
)


def state_text(bits: int) -> str:
    return " ".join(name for bit, name in STATE_NAMES if bits & bit)


class TachoMotor(Device):
    """A LEGO EV3 motor with encoder: the tacho-motor attributes and commands."""

    sysfs_class = "tacho-motor"
    name_prefix = "motor"

    def __init__(
        self, address: str, kind: str, limits_deg: tuple[float, float] | None = None, load_pct: float = 0.0
    ) -> None:
        """`limits_deg` and `load_pct`: what the shaft of a motor that drives no wheel meets (`turn_free`)."""
        driver_name, max_speed, hold_kp = KINDS[kind]
        super().__init__(address, driver_name)
        self.kind = kind
        self.max_speed = max_speed
        self.hold_kp = hold_kp
        self.count_per_rot = 360
        self.limits_deg = limits_deg  # the end stops, in degrees from where the shaft started the run
        self.load_pct = float(load_pct)
        self.angle_deg = 0.0  # where the shaft is from where it started (no command resets it)
        self.shaft_deg = 0.0  # the encoder's count in the motor's own frame (float, exact; never reset)
        # stopped, run, to_pos, timed, direct, coast; or ramped (self.ramp_kind says which run)
        self.mode = "stopped"
        self.speed_dps = 0.0  # measured shaft speed, motor frame
        self.coast_dps = 0.0
        self.last_command = ""  # the last command written (tacho_motor_class.c: tm->params.command)
        self.rel_target = 0  # the last run-to-rel-pos's target, in counts (tm->active_params.position_sp)
        self._reset()
        r, w = self.readers, self.writers
        r.update(
            commands=lambda: " ".join(COMMANDS),
            count_per_rot=lambda: str(self.count_per_rot),
            max_speed=lambda: str(self.max_speed),
            stop_actions=lambda: " ".join(STOP_ACTIONS),
            position=lambda: str(self.position),
            speed=lambda: str(self.speed),
            state=lambda: state_text(self.state_bits),
            duty_cycle=lambda: str(self.duty_cycle),
            polarity=lambda: self.polarity,
            stop_action=lambda: self.stop_action,
            speed_sp=lambda: str(self.sign * self.speed_sp),
            position_sp=lambda: str(self.sign * self.position_sp),
            time_sp=lambda: str(self.time_sp),
            duty_cycle_sp=lambda: str(self.sign * self.duty_cycle_sp),
            ramp_up_sp=lambda: str(self.ramp_up_sp),
            ramp_down_sp=lambda: str(self.ramp_down_sp),
        )
        for pid in (
            "hold_pid/Kp",
            "hold_pid/Ki",
            "hold_pid/Kd",
            "speed_pid/Kp",
            "speed_pid/Ki",
            "speed_pid/Kd",
        ):
            r[pid] = lambda pid=pid: str(self.pid[pid])
            w[pid] = lambda value, pid=pid: self.pid.__setitem__(pid, self._gain(value))
        w.update(
            command=self._command,
            polarity=self._set_polarity,
            stop_action=self._set_stop_action,
            speed_sp=self._set_speed_sp,
            position_sp=self._set_position_sp,
            time_sp=self._set_time_sp,
            duty_cycle_sp=self._set_duty_cycle_sp,
            ramp_up_sp=lambda v: setattr(self, "ramp_up_sp", self._ramp(v)),
            ramp_down_sp=lambda v: setattr(self, "ramp_down_sp", self._ramp(v)),
            position=self._set_position,
        )
        self.constants |= {"commands", "count_per_rot", "max_speed", "stop_actions"}
        self.settings |= {"polarity", "stop_action", "speed_sp", "position_sp", "time_sp", "duty_cycle_sp"}
        self.settings |= {"ramp_up_sp", "ramp_down_sp", *self.pid}
        self.write_rules.update(
            command=["choice", list(COMMANDS)],
            polarity=["choice", ["normal", "inversed"]],
            stop_action=["choice", list(STOP_ACTIONS)],
            speed_sp=int_rule(-max_speed, max_speed),
            position_sp=int_rule(),
            time_sp=int_rule(0),
            duty_cycle_sp=int_rule(-100, 100),
            ramp_up_sp=int_rule(0, 60000),
            ramp_down_sp=int_rule(0, 60000),
            position=int_rule(),
            **{pid: int_rule(0) for pid in self.pid},
        )

    # ------------------------------------------------------------ attributes
    def _reset(self) -> None:
        """The reset command (and a new motor): the settings back to the driver's defaults
        (tacho_motor_class_reset), the motor stopped with coast, so that a turning one rolls out, and
        position 0 where the shaft is now (legoev3_motor_reset: position_offset = -position)."""
        self.count_offset = -self.shaft_deg  # the count (motor frame) = shaft_deg + count_offset
        self.polarity = "normal"
        self.sign = 1  # -1 when the polarity is inversed: what position and the setpoints read
        self.stop_action = "coast"
        # the setpoints as the driver stores them: in the motor's frame, negated as read and written
        self.speed_sp = 0
        self.position_sp = 0
        self.time_sp = 0
        self.duty_cycle_sp = 0
        self.ramp_up_sp = 0
        self.ramp_down_sp = 0
        self.pid = {"hold_pid/Kp": self.hold_kp, "hold_pid/Ki": 0, "hold_pid/Kd": 0, **SPEED_PID}
        if self.mode not in ("stopped", "coast"):  # (__legoev3_motor_stop(ev3_tm, TM_STOP_ACTION_COAST))
            self.coast_dps = self.speed_dps
            self.mode = "coast"
        self.state_bits = 0
        self.target_shaft = 0.0
        self.target_count = 0  # run-to-*-pos: the target in counts (motor frame), as the driver compares it
        self.run_left_s = 0.0
        self.ramp_kind = ""  # while ramped: run, timed, to_pos or stop
        self.ramp_dps = 0.0  # while ramped: the ramp's speed now, motor frame
        self._lag_s = 0.0
        self._error_sum = 0.0  # the speed PID's integral while the shaft lags (counts/s, summed per tick)
        self._lag_duty = 0.0  # the duty cycle the speed PID drives a lagging shaft with, 0..100

    @property
    def count(self) -> float:
        """The encoder's count as the driver keeps it (motor frame, from the last reset or write)."""
        return self.shaft_deg + self.count_offset

    @property
    def position_exact(self) -> float:
        """What position reads, before it is rounded to whole counts."""
        return self.sign * self.count

    @property
    def position(self) -> int:
        return int(round(self.position_exact))

    @property
    def speed(self) -> int:
        return int(round(self.sign * self.speed_dps))

    @property
    def duty_cycle(self) -> int:
        mode = self.mode
        if mode == "stopped" or mode == "coast":
            return 0
        if mode == "direct":
            return self.sign * self.duty_cycle_sp
        dps = self._drive_dps()
        duty = self._lag_duty or min(100 * abs(dps) / self.max_speed + self.load_pct, 100.0)
        return int(round(math.copysign(duty, dps * self.sign))) if dps else 0

    def _set_position(self, value: str) -> None:
        """legoev3_motor_set_position: the count from here on, accepted also while the motor runs (its
        EBUSY test masks the state with TM_STATE_RUNNING, which is 0, so it never refuses); the written
        position also becomes a run to a position's target, so update_position ends that run here."""
        count = self.sign * parse_int(value)
        self.count_offset = count - self.shaft_deg
        if self.mode == "to_pos" or (self.mode == "ramped" and self.ramp_kind == "to_pos"):
            self.target_count, self.target_shaft = count, self.shaft_deg
            self._lag_s = 0.0
            self._stop_now()

    def _set_polarity(self, value: str) -> None:
        """polarity_store only sets the polarity: what position and the setpoints read changes sign."""
        value = value.strip()
        if value not in ("normal", "inversed"):
            raise invalid(value)
        self.polarity = value
        self.sign = -1 if value == "inversed" else 1

    def _set_stop_action(self, value: str) -> None:
        value = value.strip()
        if value not in STOP_ACTIONS:
            raise invalid(value)
        self.stop_action = value

    def _set_speed_sp(self, value: str) -> None:
        self.speed_sp = self.sign * parse_int(value, -self.max_speed, self.max_speed)

    def _set_position_sp(self, value: str) -> None:
        self.position_sp = self.sign * parse_int(value)  # (a C int's range)

    def _set_time_sp(self, value: str) -> None:
        self.time_sp = parse_int(value, 0)

    def _set_duty_cycle_sp(self, value: str) -> None:
        self.duty_cycle_sp = self.sign * parse_int(value, -100, 100)

    @staticmethod
    def _ramp(value: str) -> int:
        return parse_int(value, 0, 60000)

    @staticmethod
    def _gain(value: str) -> int:
        # tacho_motor_class.c, PID_ATTR_FUNCS: kstrtoint, then "if (k < 0) return -EINVAL;"
        return parse_int(value, 0)

    # -------------------------------------------------------------- commands
    def _command(self, value: str) -> None:
        command = value.strip()
        if command not in COMMANDS:
            raise invalid(value)
        self._run_command(command)
        self.last_command = command  # command_store: tm->params.command = i, once the command is sent

    def _run_command(self, command: str) -> None:
        self._lag_s = 0.0
        self._error_sum = 0.0
        self._lag_duty = 0.0
        if command == "run-forever":
            mode = "run"
        elif command == "run-timed":
            mode = "timed"
            self.run_left_s = self.time_sp / 1000.0
        elif command == "run-direct":
            mode = "direct"
        elif command in ("run-to-abs-pos", "run-to-rel-pos"):
            target = self.position_sp
            if command == "run-to-rel-pos":
                # tacho_motor_class.c tm_send_command: when the last command was run-to-rel-pos too
                # (running or ended), the new target is its target + position_sp, "to eliminate
                # cumulative error"; otherwise the count now + position_sp
                start = self.rel_target if self.last_command == command else int(round(self.count))
                target = self.rel_target = start + self.position_sp
                if self.position_sp == 0:
                    # "If the relative position setpoint is 0, then don't try to run, just stop."
                    self._stop()
                    return
            self.target_count = target
            self.target_shaft = target - self.count_offset
            mode = "to_pos"
        elif command == "stop":
            self._stop()
            return
        else:  # reset
            self._reset()
            return
        if mode != "direct" and (self.ramp_up_sp or self.ramp_down_sp):
            self._start_ramp(mode)
            return
        self.mode = mode
        self.state_bits = RUNNING

    def _start_ramp(self, kind: str) -> None:
        """Ramp from the speed now (the ramp's, or the measured one) toward the run's speed."""
        if self.mode != "ramped":
            self.ramp_dps = self.speed_dps if self.mode != "stopped" else 0.0
        self.mode = "ramped"
        self.ramp_kind = kind
        self.state_bits = RUNNING | RAMPING

    def _stop(self) -> None:
        if self.ramp_down_sp and self.mode in ("run", "timed", "to_pos", "ramped"):
            # a stop with ramp_down_sp ramps down to 0, then applies stop_action (tacho_motor_class.c)
            self._start_ramp("stop")
            return
        self._stop_now()

    def _stop_now(self) -> None:
        if self.stop_action == "coast" and self.mode not in ("stopped", "coast"):
            self.coast_dps = self.speed_dps
            self.mode = "coast"
            self.state_bits = 0
            return
        self.mode = "stopped"
        self.coast_dps = 0.0
        self.state_bits = HOLDING if self.stop_action == "hold" else 0

    # ----------------------------------------------------------------- ticks
    def plan(self, dt: float) -> float:
        """Degrees the shaft should turn during the coming tick of dt seconds."""
        mode = self.mode
        if mode == "stopped":
            return 0.0
        if mode == "run":
            return self.speed_sp * dt
        if mode == "to_pos":
            remaining = self.target_shaft - self.shaft_deg
            step = abs(self.speed_sp) * dt
            if abs(remaining) <= step:
                return remaining
            return math.copysign(step, remaining)
        if mode == "timed":
            return self.speed_sp * min(dt, self.run_left_s)
        if mode == "direct":
            return self.duty_cycle_sp / 100.0 * self.max_speed * dt
        if mode == "ramped":
            return self._ramp_plan(dt)[1]
        # coast: the shaft rolls out
        return self.coast_dps * COAST_TIME_CONSTANT_S * (1.0 - math.exp(-dt / COAST_TIME_CONSTANT_S))

    def _ramp_plan(self, dt: float) -> tuple[float, float, bool]:
        """A ramped run's next tick: (speed at its end, degrees turned, still ramping).

        The speed moves linearly toward the run's speed: ramp_up_sp ms for 0 to max_speed when its
        size grows, ramp_down_sp ms when it shrinks, through 0 first when the direction changes
        (tacho_motor_class.c, tacho_motor_class_start_motor_ramp).  A run to a position with
        ramp_down_sp slows down to land on it (legoev3_motor.c, update_position)."""
        kind = self.ramp_kind
        v0 = self.ramp_dps
        remaining = 0.0
        if kind == "stop":
            goal = 0.0
        elif kind == "to_pos":
            remaining = self.target_shaft - self.shaft_deg
            goal = math.copysign(abs(self.speed_sp), remaining)
        else:
            goal = float(self.speed_sp)
        leg = 0.0 if v0 * goal < 0 else goal
        ms = self.ramp_up_sp if abs(leg) > abs(v0) else self.ramp_down_sp
        need = abs(leg - v0) * ms / (1000.0 * self.max_speed)  # seconds to the leg's end
        if need > dt:
            v1 = v0 + math.copysign(dt * 1000.0 * self.max_speed / ms, leg - v0)
            distance = (v0 + v1) / 2 * dt
        else:
            v1 = leg
            distance = (v0 + leg) / 2 * need + leg * (dt - need)
        ramping = v1 != goal
        if kind == "to_pos":
            if self.ramp_down_sp and v1 * remaining > 0:
                cap = math.sqrt(2000.0 * self.max_speed / self.ramp_down_sp * abs(remaining))
                if abs(v1) > cap:
                    v1 = math.copysign(cap, remaining)
                    distance = v1 * dt
                    ramping = True
            if abs(distance) >= abs(remaining) and distance * remaining >= 0:
                distance = remaining
        elif kind == "timed" and self.run_left_s < dt:
            distance *= max(self.run_left_s, 0.0) / dt
        return v1, distance, ramping

    def turn_free(self, dt: float) -> None:
        """A tick of a motor that drives no wheel: the shaft turns as planned, less what its load takes,
        and no further than its end stops."""
        if self.load_pct and self.mode == "coast":
            self.coast_dps = 0.0  # the load stops a coasting shaft at once
        planned = self.plan(dt)
        turned = planned
        if self.load_pct and planned:
            if self.mode == "direct":  # duty d turns it at (d - load) % of max_speed
                free_pct = abs(self.duty_cycle_sp) - self.load_pct
            else:  # the speed PID drives it up to 100 % duty
                free_pct = 100.0 - self.load_pct
            reach = max(free_pct, 0.0) / 100.0 * self.max_speed * dt
            if abs(turned) > reach:
                turned = math.copysign(reach, turned)
        if self.limits_deg is not None:
            low, high = self.limits_deg
            turned = min(max(self.angle_deg + turned, low), high) - self.angle_deg
        self.angle_deg += turned
        self.measured(planned, turned, dt, stall_when_still=True)

    def measured(self, planned: float, turned: float, dt: float, stall_when_still: bool = False) -> None:
        """The shaft really turned `turned` degrees of the `planned` ones during the tick.

        A wheel's motor counts as stalled when its shaft turns less than a quarter of the plan (a robot
        held by a wall may still creep); with `stall_when_still` (a motor that drives no wheel) as the
        driver counts it: when its speed has been 0 for TACHO_MOTOR_STALLED_MS."""
        mode = self.mode
        if mode == "ramped":
            ramp_dps, _, ramping = self._ramp_plan(dt)  # before the shaft moves, as plan() saw it
        self.shaft_deg += turned
        self.speed_dps = turned / dt
        if mode == "stopped":
            return
        if mode == "coast":
            self.coast_dps *= math.exp(-dt / COAST_TIME_CONSTANT_S)
            if abs(self.coast_dps) < 5.0:
                self.mode = "stopped"
            return
        ramp_bit = 0
        if mode == "ramped":
            self.ramp_dps = ramp_dps
            mode = self.ramp_kind
            if mode == "stop" and ramp_dps == 0.0:
                self._stop_now()
                return
            if ramping:
                ramp_bit = RAMPING
            elif mode != "to_pos" or not self.ramp_down_sp:
                self.mode = mode  # at the run's speed: no more ramping work each tick
        if mode == "to_pos" and (
            abs(self.target_shaft - self.shaft_deg) < 1e-6
            or (self.speed_sp == 0 and round(self.count) == self.target_count)
        ):
            # the driver stops at once when the position reaches position_sp (update_position)
            self._lag_s = 0.0
            self._stop_now()
            return
        if mode == "timed":
            self.run_left_s -= dt
            if self.run_left_s <= 1e-9:
                self._lag_s = 0.0
                self._stop()  # ramps down first if ramp_down_sp is set (run_timed_work)
                return
        if stall_when_still:
            self._stall_when_still(planned, turned, dt, mode, ramp_bit)
            return
        # stall: a shaft that keeps turning much less than planned (or not at all, at speed 0), or
        # backwards (a robot pushed back by another); the driver reports stalled after
        # TACHO_MOTOR_STALLED_MS of no motion (update_stall)
        if abs(turned) > STALL_RATIO * abs(planned) + 1e-9 and turned * planned >= 0.0:
            if self._lag_s:  # the PID's pushing ends with the lag
                self._lag_s = self._error_sum = self._lag_duty = 0.0
            self.state_bits = RUNNING | ramp_bit
            return
        self._lag_s += dt
        bits = 0 if mode == "direct" else self._push(abs(planned - turned) / dt)
        if self._lag_s >= STALL_WINDOW_S - 1e-9:
            bits |= STALLED
        self.state_bits = RUNNING | ramp_bit | bits

    def _stall_when_still(self, planned: float, turned: float, dt: float, mode: str, ramp_bit: int) -> None:
        """State bits as legoev3_motor.c sets them: `stalled` once the speed (whole counts/s) has been 0 for
        TACHO_MOTOR_STALLED_MS while running (update_stall); `overloaded` while the speed PID, pushing a
        shaft that lags its plan, is at full duty (tm_pid_is_overloaded).  Neither ends the run."""
        bits = 0
        if abs(planned - turned) > 1e-9 and mode != "direct":
            bits = self._push(abs(planned - turned) / dt)
        elif self._lag_duty:  # the PID's pushing ends with the lag
            self._error_sum = self._lag_duty = 0.0
        if round(turned / dt) == 0:
            self._lag_s += dt  # (here: how long the shaft has stood still)
            if self._lag_s >= STALL_WINDOW_S - 1e-9:
                bits |= STALLED
        else:
            self._lag_s = 0.0
        self.state_bits = RUNNING | ramp_bit | bits

    def _drive_dps(self) -> float:
        """The speed (deg/s, motor frame) a regulated run drives the shaft at now."""
        mode = self.mode
        if mode == "ramped":
            return self.ramp_dps
        if mode == "to_pos":
            return math.copysign(abs(self.speed_sp), self.target_shaft - self.shaft_deg)
        return float(self.speed_sp)

    def _push(self, error: float) -> int:
        """The speed PID on a lagging shaft: its error (counts/s) adds up each tick and the duty cycle
        rises; past 100 % it is clamped and the motor is overloaded (tacho_motor_helper.c,
        tm_pid_update, with its anti-windup).  Kd (0 by default) is left out."""
        if not error:  # a speed setpoint of 0 drives with duty 0 (legoev3_motor_tacho_cb)
            self._lag_duty = 0.0
            return 0
        pid = self.pid
        self._error_sum += error
        duty = 100.0 * abs(self._drive_dps()) / self.max_speed + self.load_pct  # (a load needs its share)
        duty += (pid["speed_pid/Kp"] * error + pid["speed_pid/Ki"] * self._error_sum) / PID_SCALE
        if duty > 100.0:
            self._error_sum -= error
            self._lag_duty = 100.0
            return OVERLOADED
        self._lag_duty = duty
        return 0
