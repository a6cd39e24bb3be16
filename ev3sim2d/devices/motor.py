"""EV3 Large and Medium motors, as the ev3dev tacho-motor driver shows them.

Motors have infinite acceleration: a wheel turns at speed_sp at once and stops
at once on brake or hold; coast lets it roll out with a short time constant.
Each tick the motor *plans* how far its shaft should turn; the robot moves,
and the motor is told how far the shaft really turned (`measured`), which is
what the encoder counts.  A shaft that turns much less than planned for a
while (a robot pushing a wall) is `stalled`.

Runs end exactly: run-to-*-pos lands on position_sp and run-timed turns for
exactly time_sp, even when that falls between two ticks.
"""

from __future__ import annotations

import math

from .device import Device, invalid, parse_int

# ev3dev tacho-motor figures for the EV3 motors (deg/s at full power, counts per rotation)
KINDS = {
    "large": ("lego-ev3-l-motor", 1050),
    "medium": ("lego-ev3-m-motor", 1560),
}
COMMANDS = ("run-forever", "run-to-abs-pos", "run-to-rel-pos", "run-timed", "run-direct", "stop", "reset")
STOP_ACTIONS = ("coast", "brake", "hold")

COAST_TIME_CONSTANT_S = 0.08  # how quickly a coasting wheel rolls out
STALL_WINDOW_S = 0.1  # how long a shaft must lag before the motor reports stalled
STALL_RATIO = 0.25  # ... turning less than this share of the planned travel

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

    def __init__(self, address: str, kind: str) -> None:
        driver_name, max_speed = KINDS[kind]
        super().__init__(address, driver_name)
        self.kind = kind
        self.max_speed = max_speed
        self.count_per_rot = 360
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
            speed_sp=lambda: str(self.speed_sp),
            position_sp=lambda: str(self.position_sp),
            time_sp=lambda: str(self.time_sp),
            duty_cycle_sp=lambda: str(self.duty_cycle_sp),
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
            w[pid] = lambda value, pid=pid: self.pid.__setitem__(pid, parse_int(value))
        w.update(
            command=self._command,
            polarity=self._set_polarity,
            stop_action=self._set_stop_action,
            speed_sp=self._set_speed_sp,
            position_sp=lambda v: setattr(self, "position_sp", parse_int(v)),
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
            speed_sp=["int", -max_speed, max_speed],
            position_sp=["int", None, None],
            time_sp=["int", 0, None],
            duty_cycle_sp=["int", -100, 100],
            ramp_up_sp=["int", 0, 60000],
            ramp_down_sp=["int", 0, 60000],
            position=["int", None, None],
            **{pid: ["int", None, None] for pid in self.pid},
        )

    # ------------------------------------------------------------ attributes
    def _reset(self) -> None:
        self.shaft_deg = 0.0  # encoder count in the motor's own frame (float, exact)
        self.offset = 0.0  # position = sign * shaft + offset
        self.polarity = "normal"
        self.sign = 1  # -1 when the polarity is inversed
        self.stop_action = "coast"
        self.speed_sp = 0
        self.position_sp = 0
        self.time_sp = 0
        self.duty_cycle_sp = 0
        self.ramp_up_sp = 0
        self.ramp_down_sp = 0
        self.pid = {
            "hold_pid/Kp": 1000,
            "hold_pid/Ki": 0,
            "hold_pid/Kd": 0,
            "speed_pid/Kp": 1000,
            "speed_pid/Ki": 60,
            "speed_pid/Kd": 0,
        }
        self.mode = "stopped"  # stopped, run, to_pos, timed, direct, coast
        self.state_bits = 0
        self.speed_dps = 0.0  # measured shaft speed, motor frame
        self.target_shaft = 0.0
        self.run_left_s = 0.0
        self.coast_dps = 0.0
        self._lag_s = 0.0

    @property
    def position(self) -> int:
        return int(round(self.sign * self.shaft_deg + self.offset))

    @property
    def speed(self) -> int:
        return int(round(self.sign * self.speed_dps))

    @property
    def duty_cycle(self) -> int:
        return int(round(100 * self.speed_dps * self.sign / self.max_speed)) if self.mode != "stopped" else 0

    def _set_position(self, value: str) -> None:
        self.offset = parse_int(value) - self.sign * self.shaft_deg

    def _set_polarity(self, value: str) -> None:
        value = value.strip()
        if value not in ("normal", "inversed"):
            raise invalid(value)
        position = self.position
        self.polarity = value
        self.sign = -1 if value == "inversed" else 1
        self.offset = position - self.sign * self.shaft_deg

    def _set_stop_action(self, value: str) -> None:
        value = value.strip()
        if value not in STOP_ACTIONS:
            raise invalid(value)
        self.stop_action = value

    def _set_speed_sp(self, value: str) -> None:
        speed = parse_int(value)
        if abs(speed) > self.max_speed:
            raise invalid(value)
        self.speed_sp = speed

    def _set_time_sp(self, value: str) -> None:
        t = parse_int(value)
        if t < 0:
            raise invalid(value)
        self.time_sp = t

    def _set_duty_cycle_sp(self, value: str) -> None:
        duty = parse_int(value)
        if abs(duty) > 100:
            raise invalid(value)
        self.duty_cycle_sp = duty

    @staticmethod
    def _ramp(value: str) -> int:
        ms = parse_int(value)
        if not 0 <= ms <= 60000:
            raise invalid(value)
        return ms  # accepted; motors here reach their speed at once

    # -------------------------------------------------------------- commands
    def _command(self, value: str) -> None:
        command = value.strip()
        if command not in COMMANDS:
            raise invalid(value)
        self._lag_s = 0.0
        if command == "run-forever":
            self.mode = "run"
        elif command == "run-timed":
            self.mode = "timed"
            self.run_left_s = self.time_sp / 1000.0
        elif command == "run-direct":
            self.mode = "direct"
        elif command in ("run-to-abs-pos", "run-to-rel-pos"):
            target = self.position_sp + (self.position if command == "run-to-rel-pos" else 0)
            self.target_shaft = (target - self.offset) * self.sign
            self.mode = "to_pos"
        elif command == "stop":
            self._stop()
            return
        elif command == "reset":
            self._reset()
            return
        self.state_bits = RUNNING

    def _stop(self) -> None:
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
            return self.sign * self.speed_sp * dt
        if mode == "to_pos":
            remaining = self.target_shaft - self.shaft_deg
            step = abs(self.speed_sp) * dt
            if abs(remaining) <= step:
                return remaining
            return math.copysign(step, remaining)
        if mode == "timed":
            return self.sign * self.speed_sp * min(dt, self.run_left_s)
        if mode == "direct":
            return self.sign * self.duty_cycle_sp / 100.0 * self.max_speed * dt
        # coast: the shaft rolls out
        return self.coast_dps * COAST_TIME_CONSTANT_S * (1.0 - math.exp(-dt / COAST_TIME_CONSTANT_S))

    def measured(self, planned: float, turned: float, dt: float) -> None:
        """The shaft really turned `turned` degrees of the `planned` ones during the tick."""
        self.shaft_deg += turned
        self.speed_dps = turned / dt
        mode = self.mode
        if mode == "stopped":
            return
        if mode == "coast":
            self.coast_dps *= math.exp(-dt / COAST_TIME_CONSTANT_S)
            if abs(self.coast_dps) < 5.0:
                self.mode = "stopped"
            return
        if mode == "to_pos" and abs(self.target_shaft - self.shaft_deg) < 1e-6:
            self._finish_run()
            return
        if mode == "timed":
            self.run_left_s -= dt
            if self.run_left_s <= 1e-9:
                self._finish_run()
                return
        # stall: a shaft that keeps turning much less than planned
        if abs(planned) > 1e-9 and abs(turned) < STALL_RATIO * abs(planned):
            self._lag_s += dt
        else:
            self._lag_s = 0.0
        if self._lag_s >= STALL_WINDOW_S - 1e-9:
            self.state_bits = RUNNING | STALLED
        else:
            self.state_bits = RUNNING

    def _finish_run(self) -> None:
        self._lag_s = 0.0
        self._stop()
