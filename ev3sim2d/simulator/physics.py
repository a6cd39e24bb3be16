"""Pymunk bodies and shapes built from the world: static walls and robots driven by their wheels.

Walls are static boxes (the grid's wall cells merged into rectangles).  A
robot is a dynamic body whose velocity is set every tick from its wheels (the
motors have infinite acceleration), less any part of it that would push into
something it already touches: pymunk moves bodies before it solves contacts,
so a robot told to push a wall every tick would otherwise sink into it.  The
contact solver does the rest: a wall stops the robot at its face, and a robot
that meets it at an angle glides along it, slowed by friction: the part of its
velocity along the wall loses WALL_FRICTION times the part it pushes into the
wall (Coulomb's law for a body driven at a set speed: the wall pushes back as
hard as the robot pushes in, and friction takes that much of the sliding).  Shapes
of robot i are in filter group i + 1, so its own sensors never see it.

Robots push each other (`Physics._push`, only while two robots touch): along the line between
them each robot's wheels push with the power they run at (a DC motor's force falls linearly
from its full power at rest to 0 at the speed it is driven at), and a robot whose wheels do not
drive toward the other resists with what its stopped motors hold (hold, brake, coast: HOLD_PCT,
BRAKE_PCT, COAST_PCT a wheel motor) until it is pushed harder than that.  docs/simulation.md
has the model and its numbers.
"""

from __future__ import annotations

import math

import pymunk
from pymunk._chipmunk import ffi, lib  # the hot paths below call Chipmunk directly: 2-3x faster

WALL, ROBOT = 1, 2
ROBOT_MASS_KG = 0.7
# kinetic friction of a LEGO robot's ABS plastic sliding on a wall of wood or cardboard: such
# plastic-on-wood pairs measure about 0.3 to 0.5; a robot pushing a wall at 45 degrees keeps about
# 60 % of its sliding speed, head-on it stops
WALL_FRICTION = 0.4
# how hard a stopped wheel motor holds its robot against another robot's push, in % of a motor's
# full power (a robot's push is the sum of its wheel motors' power in %, up to 200 for two wheels):
# `hold` fights back with its position PID at up to full power; `brake` shorts the windings, which
# with the gear train resists about half as hard; a coasting motor has only its gears' friction
HOLD_PCT = 100.0
BRAKE_PCT = 50.0
COAST_PCT = 5.0


class RobotBody:
    """A robot's rigid body; counts its contacts, and with walls."""

    def __init__(self, body: pymunk.Body, shape: pymunk.Poly, group: int) -> None:
        self.body = body
        self._cp_body = body._body
        self.shape = shape
        self.group = group
        self.contacts = 0  # shapes touched now (walls and robots)
        self.touching = 0  # wall shapes touched now
        self.robots_touching = 0  # other robots' shapes touched now
        self.wall_contacts = 0  # times the robot started touching a wall
        # while it touches another robot (Robot.before_step sets them): how hard its wheels push,
        # the sum of the wheel motors' power in %, and how hard its stopped wheels hold, in %
        self.push_pct = 0.0
        self.hold_pct = 0.0

    def drive(self, speed: float, heading: float, turn_rate: float) -> None:
        """Move at speed (cm/s) along heading (rad) while turning at turn_rate (rad/s)."""
        vx, vy = speed * math.cos(heading), speed * math.sin(heading)
        if self.contacts:
            vx, vy = self._unblocked(vx, vy)
        lib.cpBodySetVelocity(self._cp_body, (vx, vy))
        lib.cpBodySetAngularVelocity(self._cp_body, turn_rate)

    def pose(self) -> tuple[float, float, float]:
        """x, y (cm) and heading (radians, not wrapped)."""
        p = lib.cpBodyGetPosition(self._cp_body)
        return p.x, p.y, lib.cpBodyGetAngle(self._cp_body)

    def velocity(self) -> tuple[float, float]:
        v = lib.cpBodyGetVelocity(self._cp_body)
        return v.x, v.y

    def set_velocity(self, vx: float, vy: float) -> None:
        lib.cpBodySetVelocity(self._cp_body, (vx, vy))

    def place(self, x: float, y: float, heading: float) -> None:
        """Put the body somewhere else, at rest (a hand that picks the robot up: live runs)."""
        body = self.body
        body.position = (x, y)
        body.angle = heading
        body.velocity = (0.0, 0.0)
        body.angular_velocity = 0.0
        if body.space is not None:
            body.space.reindex_shapes_for_body(body)

    def _unblocked(self, vx: float, vy: float) -> tuple[float, float]:
        """The velocity less its components into the walls the robot touches (other robots are
        pushed: Physics._push)."""
        normals = []
        shape = self.shape

        def collect(arbiter: pymunk.Arbiter) -> None:
            a, b = arbiter.shapes
            if (b if a is shape else a).collision_type != WALL:
                return
            n = arbiter.normal  # points from shapes[0] to shapes[1]
            normals.append((n.x, n.y) if a is shape else (-n.x, -n.y))

        self.body.each_arbiter(collect)
        for _ in range(2):  # twice, for corners
            for nx, ny in normals:
                into = vx * nx + vy * ny
                if into > 0:
                    vx, vy = vx - into * nx, vy - into * ny  # what is left slides along the wall
                    sliding = math.hypot(vx, vy)
                    if sliding > 0.0:  # friction takes WALL_FRICTION x the push off the sliding
                        keep = max(0.0, 1.0 - WALL_FRICTION * into / sliding)
                        vx, vy = vx * keep, vy * keep
        return vx, vy


class Physics:
    """The pymunk space of one world."""

    def __init__(self, wall_rectangles: list[tuple[float, float, float, float]]) -> None:
        space = pymunk.Space()
        space.iterations = 12
        self.space = space
        self._add_walls(wall_rectangles)
        space.on_collision(ROBOT, WALL, begin=self._begin, separate=self._separate)
        space.on_collision(ROBOT, ROBOT, begin=self._begin, separate=self._separate)
        self._cp_space = space._space
        self._query = ffi.new("cpSegmentQueryInfo *")
        self._filters: dict[int, pymunk.ShapeFilter] = {}  # per robot group: what its sensors may see
        self._probes: dict[tuple[int, float], pymunk.Segment] = {}  # touches_segment's query shapes
        self.robots: dict[pymunk.Body, RobotBody] = {}
        self.robot_pairs = 0  # robot-robot contacts now, twice (once from each robot)

    def set_walls(self, wall_rectangles: list[tuple[float, float, float, float]]) -> None:
        """Replace the walls (a cell edited during a live run)."""
        self.space.remove(*self._walls)
        self._add_walls(wall_rectangles)

    def _add_walls(self, wall_rectangles: list[tuple[float, float, float, float]]) -> None:
        space = self.space
        self._walls: list[pymunk.Poly] = []
        for x0, y0, x1, y1 in wall_rectangles:
            box = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
            box.collision_type = WALL
            box.friction = 0.0
            box.elasticity = 0.0
            space.add(box)
            self._walls.append(box)

    def add_robot(self, outline: list[tuple[float, float]], x: float, y: float, heading: float) -> RobotBody:
        """A robot body around (0, 0) = the middle of its axle, facing +x, placed at (x, y, heading)."""
        moment = pymunk.moment_for_poly(ROBOT_MASS_KG, outline)
        body = pymunk.Body(ROBOT_MASS_KG, moment)
        body.position = (x, y)
        body.angle = heading
        shape = pymunk.Poly(body, outline, radius=0.1)
        shape.collision_type = ROBOT
        shape.friction = 0.0
        shape.elasticity = 0.0
        group = len(self.robots) + 1
        shape.filter = self._filters[group] = pymunk.ShapeFilter(group=group)
        self.space.add(body, shape)
        robot = RobotBody(body, shape, group)
        self.robots[body] = robot
        return robot

    def box_touches(self, robot: RobotBody, box: tuple[float, float, float, float]) -> bool:
        """Whether the robot's body overlaps the rectangle (x0, y0, x1, y1)."""
        x0, y0, x1, y1 = box
        probe = pymunk.Poly(None, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        return any(hit.shape is robot.shape for hit in self.space.shape_query(probe))

    def overlaps_wall(self, robot: RobotBody) -> bool:
        return any(hit.shape.collision_type == WALL for hit in self.space.shape_query(robot.shape))

    def _begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: object) -> None:
        self._count(arbiter, +1)

    def _separate(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: object) -> None:
        self._count(arbiter, -1)

    def _count(self, arbiter: pymunk.Arbiter, change: int) -> None:
        a, b = arbiter.shapes
        for mine, other in ((a, b), (b, a)):
            robot = self.robots.get(mine.body)
            if robot is None:
                continue
            robot.contacts = max(robot.contacts + change, 0)
            if other.collision_type == ROBOT:
                robot.robots_touching = max(robot.robots_touching + change, 0)
                self.robot_pairs = max(self.robot_pairs + change, 0)  # (counted once for each side)
            elif other.collision_type == WALL:
                if change > 0 and robot.touching == 0:
                    robot.wall_contacts += 1
                robot.touching = max(robot.touching + change, 0)

    def step(self, dt: float) -> None:
        # Chipmunk's step itself: nothing is added or removed while the world runs, which is all
        # pymunk's Space.step adds around it (at a dozen Python calls a tick).
        if self.robot_pairs:
            self._push()
        lib.cpSpaceStep(self._cp_space, dt)

    def _push(self) -> None:
        """Settle, for each pair of touching robots, how fast they move along the line between
        them; their velocities (set by drive) are what their wheels want, less the walls."""
        pairs = []
        for robot in self.robots.values():  # in the order the robots were added: deterministic
            if not robot.robots_touching:
                continue

            def collect(arbiter: pymunk.Arbiter, robot: RobotBody = robot) -> None:
                a, b = arbiter.shapes
                them = self.robots.get((b if a is robot.shape else a).body)
                if them is None or them.group < robot.group:
                    return  # a wall, or a pair already taken from the other side
                n = arbiter.normal  # from shapes[0] to shapes[1]
                nx, ny = (n.x, n.y) if a is robot.shape else (-n.x, -n.y)
                pairs.append((robot, them, nx, ny))

            robot.body.each_arbiter(collect)
        for a, b, nx, ny in pairs:
            _push_pair(a, b, nx, ny)

    def ray(self, x: float, y: float, direction: float, max_cm: float, group: int) -> float | None:
        """Distance from (x, y) along direction to the first wall or other robot, if within max_cm."""
        end = (x + max_cm * math.cos(direction), y + max_cm * math.sin(direction))
        hit = lib.cpSpaceSegmentQueryFirst(
            self._cp_space, (x, y), end, 0.0, self._filters[group], self._query
        )
        return None if hit == ffi.NULL else self._query.alpha * max_cm

    def touches_segment(
        self, x0: float, y0: float, x1: float, y1: float, reach_cm: float, group: int
    ) -> bool:
        """Whether a wall or another robot is within reach_cm of the segment (x0, y0)-(x1, y1).  (A shape
        query with a thick segment: a segment query would miss a wall the segment already touches.)"""
        probe = self._probes.get((group, reach_cm))
        if probe is None:
            probe = self._probes[(group, reach_cm)] = pymunk.Segment(None, (0, 0), (0, 0), reach_cm)
            probe.body = self.space.static_body
            probe.filter = self._filters[group]
        probe.unsafe_set_endpoints((x0, y0), (x1, y1))
        return bool(self.space.shape_query(probe))

    def near(self, x: float, y: float, reach_cm: float, group: int) -> bool:
        """Whether a wall or another robot is within reach_cm of (x, y)."""
        return self.space.point_query_nearest((x, y), reach_cm, self._filters[group]) is not None


def _push_pair(a: RobotBody, b: RobotBody, nx: float, ny: float) -> None:
    """Robots a and b touch, n = (nx, ny) pointing from a to b: set how fast both move along n.

    Along n each robot is a motor: one that drives toward the other at free speed s with power P
    pushes with P * (1 - v / s) at speed v; one that does not resists with what its wheels hold (a
    stopped motor's HOLD_PCT/BRAKE_PCT/COAST_PCT, a driving one's power) and moves only when pushed
    harder.  Both pushing: they move where their forces balance, v = (Pa - Pb) / (Pa/sa + Pb/sb)
    (equal pushes stall each other).  The parts across n are each robot's own."""
    avx, avy = a.velocity()
    bvx, bvy = b.velocity()
    sa = avx * nx + avy * ny  # a's speed toward b
    sb = -(bvx * nx + bvy * ny)  # b's speed toward a
    if sa + sb <= 0.0:
        return  # they part (or one follows the other no faster than it goes)
    pa, pb = a.push_pct, b.push_pct
    if sa > 0.0 and sb > 0.0:
        weight = pa / sa + pb / sb
        v = (pa - pb) / weight if weight > 0.0 else 0.0
    elif sa > 0.0:  # b does not drive toward a: it holds, or goes away slower than a comes
        hold = b.hold_pct + pb
        v = max(-sb, sa * (1.0 - hold / pa) if pa > hold else 0.0)
    else:
        hold = a.hold_pct + pa
        v = -max(-sa, sb * (1.0 - hold / pb) if pb > hold else 0.0)
    avx, avy = avx + (v - sa) * nx, avy + (v - sa) * ny
    bvx, bvy = bvx + (v + sb) * nx, bvy + (v + sb) * ny
    if a.touching:  # a pushed back into a wall stops there
        avx, avy = a._unblocked(avx, avy)
    if b.touching:
        bvx, bvy = b._unblocked(bvx, bvy)
    va, vb = avx * nx + avy * ny, bvx * nx + bvy * ny
    if va > vb + 1e-9:  # one of them is held by a wall: the other cannot go through it
        if vb < v - 1e-9:  # b is blocked: a stops with it
            avx, avy = avx + (vb - va) * nx, avy + (vb - va) * ny
        else:  # a is blocked: b goes no faster toward a
            bvx, bvy = bvx + (va - vb) * nx, bvy + (va - vb) * ny
    a.set_velocity(avx, avy)
    b.set_velocity(bvx, bvy)
