"""What a run left behind for the checks: its trace and world, as arrays a check can ask questions of.

Row 0 of every array is the start (t = 0); row i is the end of tick i.  Only
the trace, the world (with the variant's start and robot) and what the worker
saw of the motors at the very end are read: never the live simulation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..results.trace import POSE_COLUMNS, Trace
from ..world.world import World

MOVING_CM = 1e-3  # a pose change below this between ticks is standing still


@dataclass
class RunRecord:
    """One robot's run in one variant: trace + world, with the arrays checks read (`robot`: which of
    the run's robots, in the order of their starts)."""

    trace: Trace
    world: World
    time_limit_s: float | None
    robot: int = 0
    _cache: dict = field(default_factory=dict, repr=False)

    # -- how the run ended ---------------------------------------------------------------
    @property
    def status(self) -> str:
        """finished, error, time_limit, hung or interrupted (as run_programs said)."""
        return self.trace.result.get("status", "finished")

    @property
    def error(self) -> dict | None:
        return self.trace.result.get("error")

    @property
    def end_s(self) -> float:
        """The simulated time when the run ended."""
        return float(self.trace.result.get("sim_time_s", self.t[-1]))

    # -- the robot's motion ----------------------------------------------------------------
    @property
    def t(self) -> np.ndarray:
        """Time of each row, seconds."""
        if "t" not in self._cache:
            self._cache["t"] = np.concatenate([[0.0], np.asarray(self.trace.times, dtype=float)])
        return self._cache["t"]

    @property
    def poses(self) -> np.ndarray:
        """rows × (x_cm, y_cm, heading_deg), heading counter-clockwise and not wrapped."""
        if "poses" not in self._cache:
            self._cache["poses"] = self.trace.poses(self.robot)
        return self._cache["poses"]

    @property
    def xy(self) -> np.ndarray:
        return self.poses[:, :2]

    @property
    def heading_deg(self) -> np.ndarray:
        return self.poses[:, 2]

    @property
    def start(self) -> tuple[float, float, float]:
        s = self.trace.robots[self.robot]["start"]
        return (float(s["x_cm"]), float(s["y_cm"]), float(s["heading_deg"]))

    def _motion_columns(self) -> np.ndarray:
        if "motion" not in self._cache:
            motion = self.trace.motion()
            self._cache["motion"] = motion[:, self.trace.robot_columns(self.robot)] if len(motion) else motion
        return self._cache["motion"]

    def for_robot(self, index: int) -> RunRecord:
        """The same run seen from another of its robots (index in the order of their starts)."""
        if index == self.robot:
            return self
        return RunRecord(self.trace, self.world, self.time_limit_s, index)

    def _flag(self, column: str) -> np.ndarray:
        if column not in self._cache:
            m = self._motion_columns()
            values = m[:, POSE_COLUMNS.index(column)] > 0.5 if len(m) else np.zeros(0, dtype=bool)
            self._cache[column] = np.concatenate([[False], values])
        return self._cache[column]

    @property
    def touching(self) -> np.ndarray:
        """Whether the body touches a wall, per row (False at the start)."""
        return self._flag("touching")

    @property
    def touching_robot(self) -> np.ndarray:
        """Whether the body touches another robot, per row (False at the start)."""
        return self._flag("touching_robot")

    def wheel_speeds(self) -> np.ndarray:
        """rows × 2: the left and right wheel motors' speed (degrees/s), 0 at the start."""
        if "wheels" not in self._cache:
            info = self.trace.robots[self.robot]
            ports = [port for port, _kind in info["motors"]]
            m = self._motion_columns()
            speeds = []
            for wheel in info["wheels"]:
                col = len(POSE_COLUMNS) + 3 * ports.index(wheel) + 1
                speeds.append(m[:, col] if len(m) else np.zeros(0))
            table = np.column_stack(speeds) if len(m) else np.zeros((0, 2))
            self._cache["wheels"] = np.vstack([np.zeros((1, 2)), table])
        return self._cache["wheels"]

    @property
    def path_cm(self) -> float:
        steps = np.diff(self.xy, axis=0)
        return float(np.hypot(steps[:, 0], steps[:, 1]).sum()) if len(steps) else 0.0

    def step_lengths(self, point: str = "centre") -> np.ndarray:
        """How far the point moved during each row (0 for row 0)."""
        track = self.track(point)
        steps = np.diff(track, axis=0)
        return np.concatenate([[0.0], np.hypot(steps[:, 0], steps[:, 1])])

    def driving_at_end(self) -> bool:
        """Whether the wheel motors were still driving when the run ended (they keep going after a program ends)."""
        end = self.trace.end_motors
        if self.robot < len(end):
            return bool(end[self.robot].get("driving"))
        speeds = self.wheel_speeds()
        return bool(np.any(np.abs(speeds[-1]) > 1.0))

    def last_moved_s(self) -> float:
        """The time the robot last moved (0 if it never did)."""
        moves = np.flatnonzero(self.step_lengths() > MOVING_CM)
        steps = np.abs(np.diff(self.heading_deg))
        turns = np.flatnonzero(steps > 1e-3)
        last = max(moves[-1] if len(moves) else 0, (turns[-1] + 1) if len(turns) else 0)
        return float(self.t[last])

    # -- points of the robot ---------------------------------------------------------------
    def offset_of(self, point: str) -> tuple[float, float]:
        """(forward, left) cm of a named point of the robot from its centre."""
        spec = self.world.start_robot(self.robot)
        if point == "centre":
            return (0.0, 0.0)
        if point == "front":
            return (spec.body.front_cm, 0.0)
        if point == "color-sensor":
            sensor = next((s for s in spec.sensors if s.kind == "color"), None)
            if sensor is None:
                raise ValueError("the robot has no colour sensor")
            return sensor.offset_cm
        raise ValueError(f"unknown point of the robot: {point!r}")

    def track(self, point: str = "centre") -> np.ndarray:
        """rows × (x, y) cm of the point."""
        key = ("track", point)
        if key not in self._cache:
            forward, left = self.offset_of(point)
            if forward == 0 and left == 0:
                self._cache[key] = self.xy
            else:
                h = np.radians(self.heading_deg)
                x = self.xy[:, 0] + forward * np.cos(h) - left * np.sin(h)
                y = self.xy[:, 1] + forward * np.sin(h) + left * np.cos(h)
                self._cache[key] = np.column_stack([x, y])
        return self._cache[key]

    def from_start(self, forward_cm: float, left_cm: float) -> tuple[float, float]:
        """The world point `forward_cm` ahead of and `left_cm` to the left of the start pose."""
        x, y, heading = self.start
        h = math.radians(heading)
        return (
            x + forward_cm * math.cos(h) - left_cm * math.sin(h),
            y + forward_cm * math.sin(h) + left_cm * math.cos(h),
        )

    def index_at(self, t_s: float) -> int:
        return int(min(np.searchsorted(self.t, t_s, side="right") - 1, len(self.t) - 1))


def region_distance(world: World, region: str, xy: np.ndarray) -> np.ndarray:
    """Distance (cm) from each point to the region: 0 inside it."""
    best = np.full(len(xy), np.inf)
    for x0, y0, x1, y1 in world.region(region).rects:
        dx = np.maximum.reduce([x0 - xy[:, 0], np.zeros(len(xy)), xy[:, 0] - x1])
        dy = np.maximum.reduce([y0 - xy[:, 1], np.zeros(len(xy)), xy[:, 1] - y1])
        best = np.minimum(best, np.hypot(dx, dy))
    return best


def region_inside(world: World, region: str, xy: np.ndarray) -> np.ndarray:
    """Whether each point lies in the region (edges as Region.contains)."""
    inside = np.zeros(len(xy), dtype=bool)
    for x0, y0, x1, y1 in world.region(region).rects:
        inside |= (xy[:, 0] >= x0) & (xy[:, 0] < x1) & (xy[:, 1] >= y0) & (xy[:, 1] < y1)
    return inside


def seconds(t: float) -> str:
    """A simulated time as students read it: '12.4 s'."""
    return f"{t:.1f} s"
