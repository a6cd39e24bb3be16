"""A run's values against time, by name: each robot's pose, sensor readings and motors at every tick.

Read from a Trace for the Python API, its tables and plots (and `ev3sim2d plot` on a saved trace).
The first row is the start (t = 0 s); then one row per tick.  A sensor's value at a tick is its last
measurement up to then (what the program would have read), NaN before the first one.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from .trace import MOTOR_COLUMNS, POSE_COLUMNS, Trace

_EPS_S = 1e-9


@dataclass
class RobotSeries:
    """One robot's timelines, each an array with one entry per time in `times`."""

    name: str
    times: np.ndarray  # seconds, 0 first
    poses: np.ndarray  # rows of (x_cm, y_cm, heading_deg)
    touching: np.ndarray  # bool: the body touches a wall
    sensors: dict[str, np.ndarray]  # port ('in3') -> the first value of each reading (e.g. reflected light)
    sensor_kinds: dict[str, str]  # port -> kind ('color', 'gyro', ...)
    motors: dict[str, np.ndarray]  # 'outB.speed' (deg/s), 'outB.position' (deg) -> values

    def columns(self) -> dict[str, np.ndarray]:
        """Every timeline by name: t_s, x_cm, y_cm, heading_deg, touching, the sensors, the motors."""
        named = {
            "t_s": self.times,
            "x_cm": self.poses[:, 0],
            "y_cm": self.poses[:, 1],
            "heading_deg": self.poses[:, 2],
            "touching": self.touching.astype(float),
        }
        return {**named, **self.sensors, **self.motors}

    def column(self, name: str) -> np.ndarray:
        """One timeline by name; KeyError listing the names there are otherwise."""
        columns = self.columns()
        if name not in columns:
            raise KeyError(f"no timeline {name!r} for {self.name}; there are: {', '.join(columns)}")
        return columns[name]


def robot_series(trace: Trace, index: int = 0) -> RobotSeries:
    """The timelines of robot `index` (0 for the first program's robot)."""
    robot = trace.robots[index]
    ticks = np.asarray(trace.times, dtype=float)
    times = np.concatenate([[0.0], ticks])
    motion = trace.motion()[:, trace.robot_columns(index)]
    touching = np.concatenate([[False], motion[:, POSE_COLUMNS.index("touching")] > 0.5])
    motors: dict[str, np.ndarray] = {}
    for m, (port, _kind) in enumerate(robot["motors"]):
        first = len(POSE_COLUMNS) + m * len(MOTOR_COLUMNS)
        for name in ("speed", "position"):
            values = motion[:, first + MOTOR_COLUMNS.index(name)]
            motors[f"{port}.{name}"] = np.concatenate([[0.0], values])
    sensors = {port: _held(trace, index, port, times) for port, _kind in robot["sensors"]}
    return RobotSeries(
        name=robot["name"],
        times=times,
        poses=trace.poses(index),
        touching=touching,
        sensors=sensors,
        sensor_kinds={port: kind for port, kind in robot["sensors"]},
        motors=motors,
    )


def _held(trace: Trace, robot: int, port: str, times: np.ndarray) -> np.ndarray:
    """A sensor's first value at each time: its last measurement up to then, NaN before any."""
    return held_readings(trace, robot, port, times, lambda _mode, values: float(values[0]))


def held_readings(
    trace: Trace, robot: int, port: str, times: np.ndarray, reading: Callable[[str, list], float]
) -> np.ndarray:
    """`reading(mode, values)` of a sensor's last measurement up to each time, NaN before any (the plot
    uses it to give each reading in its mode's unit)."""
    samples = [
        (t, reading(mode, values))
        for t, r, p, mode, values in trace.sensor_samples
        if r == robot and p == port
    ]
    out = np.full(len(times), np.nan)
    if not samples:
        return out
    sample_t = np.array([t for t, _ in samples], dtype=float)
    sample_v = np.array([v for _, v in samples], dtype=float)
    at = np.searchsorted(sample_t, times + _EPS_S, side="right") - 1
    seen = at >= 0
    out[seen] = sample_v[at[seen]]
    return out
