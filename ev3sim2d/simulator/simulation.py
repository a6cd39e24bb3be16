"""The world in motion: physics, robots and their devices, stepped tick by tick into a Trace.

The simulation knows nothing of programs, rendering or grading: the
scheduler calls `tick()`, and whoever drives the devices (the ev3dev2 shim,
through a link) goes through each robot's brick.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..devices.motor import state_text
from ..results.trace import Trace
from ..world.cell import WALL_SHADE, Cell
from ..world.colors import DEFAULT_SURFACES, Surfaces
from ..world.grid import Grid
from ..world.pose import Pose
from ..world.robot_spec import RobotSpec
from ..world.world import World
from .physics import Physics
from .robot import Robot

DEGREES = 180.0 / math.pi
TICK_US = 10_000  # the world advances in steps of 10 ms of virtual time
SENSOR_SNAPSHOT_EVERY = 10  # every 10 ticks (10 Hz) each sensor is measured for the trace, read or not


@dataclass
class Floor:
    """The grid as the colour sensor reads it: plain row-major tables, fast to index."""

    cell_cm: float
    width: int
    height: int
    reflected: list
    color_id: list
    raw_rgb: list

    @classmethod
    def of(cls, grid: Grid, surfaces: Surfaces = DEFAULT_SURFACES) -> Floor:
        """The tables of the grid's cells, with the readings of the world's `surfaces` (its calibration)."""
        if surfaces.is_default:
            reflected, raw_rgb = grid.reflected_rows(), grid.raw_rgb_rows()
        else:
            rows = [[grid.cell(col, row) for col in range(grid.width)] for row in range(grid.height)]
            paint = [[(c.color, WALL_SHADE if c.shade is None else c.shade) for c in cells] for cells in rows]
            reflected = [[surfaces.reflected(*p) for p in cells] for cells in paint]
            raw_rgb = [[surfaces.raw_rgb(*p) for p in cells] for cells in paint]
        return cls(grid.cell_cm, grid.width, grid.height, reflected, grid.color_id_rows(), raw_rgb)


class StartBlocked(ValueError):
    """A robot's start pose puts its body inside a wall."""


class Simulation:
    """A world with its robots, advanced one tick at a time."""

    def __init__(
        self, world: World, robots: list[tuple[str, RobotSpec, Pose]], seed: int = 0, tick_us: int = TICK_US
    ) -> None:
        self.world = world
        self.tick_us = tick_us
        self.dt = tick_us / 1e6
        self.rng = np.random.default_rng(seed)
        self.physics = Physics(world.grid.wall_rectangles())
        surfaces = self.surfaces = getattr(world, "surfaces", DEFAULT_SURFACES)
        floor = self.floor = Floor.of(world.grid, surfaces)
        ambient = float(getattr(world, "ambient", 10.0) or 10.0)
        self.robots = [
            Robot(name, spec, pose, self.physics, floor, self.rng, ambient) for name, spec, pose in robots
        ]
        self._let_go: dict[int, dict] = {}  # robots whose programs ended while others ran: how they were
        for robot in self.robots:
            if self.physics.overlaps_wall(robot.body):
                p = robot.start
                raise StartBlocked(
                    f"{robot.name} starts at x={p.x_cm:g} cm, y={p.y_cm:g} cm, heading {p.heading_deg:g}° "
                    f"with its body inside a wall; move the start further from the walls"
                )
        if len(self.robots) > 1:  # each hears the others' speakers
            for robot in self.robots:
                robot.others = [r for r in self.robots if r is not robot]
        self._sounds_seen = 0  # the trace's events already looked at for the speakers' volumes
        self.ticks = 0
        self.trace = Trace(
            tick_s=self.dt,
            robots=[self._describe(r) for r in self.robots],
            world={"name": world.name, "title": world.title, "text": world.text},
            seed=seed,
        )

    @staticmethod
    def _describe(robot: Robot) -> dict:
        return {
            "name": robot.name,
            "start": robot.start.as_dict(),
            "motors": [[port, m.kind] for port, m in robot.motors.items()],
            "sensors": [[port, s.spec.kind] for port, s in robot.sensors.items()],
            "wheels": [robot.spec.left_wheel.port, robot.spec.right_wheel.port],
            "body": robot.spec.body.__dict__ if hasattr(robot.spec.body, "__dict__") else None,
            "wheel_diameter_mm": robot.spec.wheel_diameter_mm,
            "axle_track_mm": robot.spec.axle_track_mm,
            "color": list(robot.spec.color),
            # where each sensor sits and what it sees, in the order of "sensors" (for drawing)
            "sensor_mounts": [
                {
                    "port": port,
                    "kind": s.spec.kind,
                    "angle_deg": s.spec.angle_deg,
                    "radius_cm": s.spec.radius_cm,
                    "facing": s.spec.facing,
                    "aim_deg": s.spec.aim_deg,
                    **s.spec.options,
                }
                for port, s in robot.sensors.items()
            ],
        }

    def finish(self) -> Trace:
        """The trace, with the sensor measurements collected from the sensors, in time order."""
        samples = [
            [tick * self.dt, index, port, mode, list(values)]
            for index, robot in enumerate(self.robots)
            for port, sensor in robot.sensors.items()
            for tick, mode, values in sensor.samples
        ]
        samples.sort(key=lambda s: (s[0], s[1], s[2]))
        self.trace.sensor_samples = samples
        # the last tick may come before the program's last commands (a tank.off() just before it ends)
        self.trace.end_motors = [
            self._let_go.get(i) or self._motors_now(robot) for i, robot in enumerate(self.robots)
        ]
        return self.trace

    def _motors_now(self, robot: Robot) -> dict:
        return {"driving": robot.driving(), "states": self.motor_states(robot)}

    # --------------------------------------------------- a hand in the world (live runs)
    def place_robot(self, index: int, x_cm: float, y_cm: float, heading_deg: float) -> None:
        """Pick robot `index` up and put it down elsewhere, between two ticks; the trace records it (an
        event 'place'), so that a replay shows the jump.  ValueError where its body would be in a wall
        or outside the world (it is not moved then)."""
        robot = self.robots[index]
        check_place(self.world, index, x_cm, y_cm, heading_deg)
        before = robot.x, robot.y, math.degrees(robot.heading_rad)
        robot.place(x_cm, y_cm, heading_deg)
        if self.physics.overlaps_wall(robot.body):
            robot.place(*before)
            raise ValueError(
                f"robot {index + 1} cannot stand at ({x_cm:.1f}, {y_cm:.1f}) cm: it would be in a wall"
            )
        self.trace.add_event(
            self._now_s(), index, "place", {"x_cm": x_cm, "y_cm": y_cm, "heading_deg": heading_deg}
        )

    def set_cell(self, col: int, row: int, cell: Cell) -> None:
        """Change one cell of the world between two ticks: its walls and floor as the robots meet and
        read them from the next tick on; the trace records it (an event 'cell').  ValueError for a wall
        where a robot stands, or a border cell made floor (the robots must not leave the world)."""
        grid = self.world.grid
        border = col in (0, grid.width - 1) or row in (0, grid.height - 1)
        if border and not cell.wall:
            raise ValueError(f"cell ({col}, {row}) is on the border: it stays a wall")
        if cell.wall:
            s = grid.cell_cm
            box = (col * s, row * s, (col + 1) * s, (row + 1) * s)
            for i, robot in enumerate(self.robots):
                if self.physics.box_touches(robot.body, box):
                    raise ValueError(f"cell ({col}, {row}) is under robot {i + 1}: move the robot first")
        self.world.set_cell(col, row, cell)
        fresh = Floor.of(self.world.grid, self.surfaces)
        for name in ("reflected", "color_id", "raw_rgb"):  # the sensors hold this Floor: change it in place
            getattr(self.floor, name)[:] = getattr(fresh, name)
        self.physics.set_walls(self.world.grid.wall_rectangles())
        self.trace.add_event(
            self._now_s(), -1, "cell", {"col": col, "row": row, "wall": cell.wall, "shade": cell.shade,
                                       "color": cell.color},
        )  # fmt: skip

    def _now_s(self) -> float:
        return self.trace.times[-1] if self.trace.times else 0.0

    def let_go(self, index: int) -> None:
        """Robot `index`'s program ended (or its brick was dropped) while other robots' programs run on.

        As brickman does on an EV3 when a program it started ends, the robot's motors are reset: they
        stop and coast, and their settings go back to the defaults.  How they were when the program
        ended is what the trace's end_motors keeps (what the program left them doing)."""
        robot = self.robots[index]
        self._let_go[index] = self._motors_now(robot)
        for motor in robot.motors.values():
            motor.write("command", "reset")

    def tick(self, now_us: int) -> None:
        """Advance the world by one tick ending at now_us, and record it."""
        dt = self.dt
        robots = self.robots
        for robot in robots:
            robot.before_step(dt)
        self.physics.step(dt)
        row: list = []
        add = row.extend
        for robot in robots:
            robot.after_step(dt)
            body = robot.body
            add((
                robot.x,
                robot.y,
                robot.heading_rad * DEGREES,
                1.0 if body.touching else 0.0,
                1.0 if body.robots_touching else 0.0,
            ))  # fmt: skip
            for motor in robot.motors.values():  # (position_exact spelt out: two properties a motor a tick)
                sign = motor.sign
                add((sign * (motor.shaft_deg + motor.count_offset), motor.speed_dps * sign, motor.state_bits))
        if len(self.trace.events) > self._sounds_seen and len(self.robots) > 1:
            self._follow_volumes()
        t = now_us / 1e6
        self.trace.add_tick(t, row)
        self.ticks += 1
        if self.ticks % SENSOR_SNAPSHOT_EVERY == 0:
            for robot in self.robots:
                for sensor in robot.sensors.values():
                    sensor.values()  # measured (and so recorded) unless the program did this tick

    def _follow_volumes(self) -> None:
        """Each robot's speaker volume, from its brick's sound events since the last tick (set_volume
        sets it; a sound with a volume of its own plays at that), for the others' sound sensors."""
        events = self.trace.events
        for _, index, kind, data in events[self._sounds_seen :]:
            if kind != "sound" or not 0 <= index < len(self.robots):
                continue
            volume = data.get("pct") if data.get("kind") == "set_volume" else data.get("volume")
            if volume is not None:
                self.robots[index].sound_volume = float(volume)
        self._sounds_seen = len(events)

    def motor_states(self, robot: Robot) -> dict[str, str]:
        return {port: state_text(m.state_bits) for port, m in robot.motors.items()}


def check_place(world: World, index: int, x_cm: float, y_cm: float, heading_deg: float) -> None:
    """ValueError, saying why, for a place no robot can be put at: outside the world, or a heading beyond a
    turn either way (as a world file's start: world/file_limits.py); NaN is neither."""
    width, height = world.grid.size_cm
    if not (0 <= x_cm <= width and 0 <= y_cm <= height):
        raise ValueError(
            f"robot {index + 1} cannot stand at ({x_cm:.4g}, {y_cm:.4g}) cm: outside the world "
            f"(x 0 to {width:g}, y 0 to {height:g} cm)"
        )
    if not -360 <= heading_deg <= 360:
        raise ValueError(f"a heading of {heading_deg:.4g} degrees: give one from -360 to 360")
