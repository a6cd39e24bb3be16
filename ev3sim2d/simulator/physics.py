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
import struct
from collections.abc import Callable

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
# Physics.cone: the widest part of a cone asked at once (a wider cone is asked in parts), and how far
# short of what the cone's edges found its query shape stops, so that it does not touch that
CONE_PART_RAD = math.radians(60.0)
CONE_GAP_CM = 1e-6
_pack_five, _pack_four = struct.Struct("10d").pack_into, struct.Struct("8d").pack_into
_unpack_hit = struct.Struct("3d").unpack_from  # a segment query's normal and alpha
_HIT_AT = ffi.offsetof("cpSegmentQueryInfo", "normal")
_unpack_point = struct.Struct("2d").unpack_from  # a point query's point
_POINT_AT = ffi.offsetof("cpPointQueryInfo", "point")
# Chipmunk's functions that Physics.cone calls, looked up once
_segment_first, _shape_nearest = lib.cpSpaceSegmentQueryFirst, lib.cpShapePointQuery
_set_corners, _anything_in, _NULL = lib.cpPolyShapeSetVertsRaw, lib.cpSpaceShapeQuery, ffi.NULL
_cos, _sin, _sqrt = math.cos, math.sin, math.sqrt


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
        # Chipmunk's arbiters of its contacts now (begin to separate), and what they say, read at most once
        # a tick (`contacts_now`): the walls' normals, and the robots touched with the normal toward each
        self.arbiters: dict = {}
        self._read = False
        self._wall_normals: list[tuple[float, float]] = []
        self._robot_contacts: list[tuple[RobotBody, float, float]] = []
        self._robot_of: dict = {}  # every robot's shape (Chipmunk's pointer) -> its RobotBody (Physics')

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

    def contacts_now(self) -> tuple[list[tuple[float, float]], list[tuple[RobotBody, float, float]]]:
        """The normals (out of the robot) of the walls it touches, and the robots it touches with the normal
        toward each, in the order of Chipmunk's arbiter list of its body (what each_arbiter gives), read
        from Chipmunk's structs once between two steps (Physics.step marks them stale)."""
        if not self._read:
            self._read = True
            walls, robots = self._wall_normals, self._robot_contacts
            walls.clear()
            robots.clear()
            if self.arbiters:
                body, robot_of = self._cp_body, self._robot_of
                arbiter = next(iter(self.arbiters))  # one of the body's list: back to its head, then along
                while True:
                    before = arbiter.thread_a.prev if arbiter.body_a == body else arbiter.thread_b.prev
                    if before == _NULL:
                        break
                    arbiter = before
                while arbiter != _NULL:
                    n = arbiter.n  # points from shape a to shape b
                    if arbiter.body_a == body:
                        other, nx, ny, arbiter = arbiter.b, n.x, n.y, arbiter.thread_a.next
                    else:
                        other, nx, ny, arbiter = arbiter.a, -n.x, -n.y, arbiter.thread_b.next
                    them = robot_of.get(other)
                    if them is None:
                        walls.append((nx, ny))
                    else:
                        robots.append((them, nx, ny))
        return self._wall_normals, self._robot_contacts

    def _unblocked(self, vx: float, vy: float) -> tuple[float, float]:
        """The velocity less its components into the walls the robot touches (other robots are
        pushed: Physics._push)."""
        normals = self.contacts_now()[0]
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
        self._cone_queries: dict[int, Callable[..., float | None]] = {}  # per robot group: cone()
        self.robots: dict[pymunk.Body, RobotBody] = {}
        self.robot_pairs = 0  # robot-robot contacts now, twice (once from each robot)
        self._robot_of: dict = {}  # each robot's shape, as Chipmunk's pointer, -> its RobotBody

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
        robot._robot_of = self._robot_of
        self._robot_of[shape._shape] = robot
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
            if change > 0:
                robot.arbiters[arbiter._arbiter] = None
            else:
                robot.arbiters.pop(arbiter._arbiter, None)
            robot._read = False
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
        for robot in self.robots.values():  # their contacts are read afresh after each step
            robot._read = False

    def _push(self) -> None:
        """Settle, for each pair of touching robots, how fast they move along the line between
        them; their velocities (set by drive) are what their wheels want, less the walls."""
        pairs = []
        for robot in self.robots.values():  # in the order the robots were added: deterministic
            if robot.robots_touching:
                for them, nx, ny in robot.contacts_now()[1]:
                    if them.group > robot.group:  # (a pair is taken from the robot added first)
                        pairs.append((robot, them, nx, ny))
        for a, b, nx, ny in pairs:
            _push_pair(a, b, nx, ny)

    def ray(self, x: float, y: float, direction: float, max_cm: float, group: int) -> float | None:
        """Distance from (x, y) along direction to the first wall or other robot, if within max_cm."""
        end = (x + max_cm * math.cos(direction), y + max_cm * math.sin(direction))
        hit = lib.cpSpaceSegmentQueryFirst(
            self._cp_space, (x, y), end, 0.0, self._filters[group], self._query
        )
        return None if hit == ffi.NULL else self._query.alpha * max_cm

    def cone(
        self, x: float, y: float, direction: float, half_rad: float, max_cm: float, group: int
    ) -> float | None:
        """Distance from (x, y) to the nearest point of a wall or other robot inside the cone of half-angle
        half_rad around direction, if within max_cm (None: nothing).  Robot `group`'s sensors ask it
        through `cone_query(group)`.

        Exact, so a corner anywhere in the cone is seen on every tick, and deterministic.  Walls and
        robots are convex, and the nearest point of a convex shape inside a cone is either the shape's
        nearest point to the apex (when that lies in the cone) or where one of the cone's two edges
        first meets it.  So: the two edges' first hits (segment queries); the nearest points of the
        shapes they hit; then one query, in C alone, whether anything else reaches into the sector
        nearer than that (a polygon round the sector that those shapes do not reach).  Only if
        something does is each shape that polygon meets asked for its nearest point.  It costs about
        what the three rays it replaces cost."""
        return self.cone_query(group)(x, y, direction, half_rad, max_cm)

    def cone_query(self, group: int) -> Callable[[float, float, float, float, float], float | None]:
        """`cone` for robot `group`'s sensors: a function of (x, y, direction, half_rad, max_cm), made once
        per group with what it needs at hand (it runs for every ultrasonic and infrared reading)."""
        query = self._cone_queries.get(group)
        if query is None:
            query = self._cone_queries[group] = self._new_cone_query(group)
        return query

    def _new_cone_query(self, group: int) -> Callable[[float, float, float, float, float], float | None]:
        space, shape_query = self._cp_space, self.space.shape_query
        sector = pymunk.Poly(self.space.static_body, [(0, 0), (1, 0), (0, 1)])  # moved for each query
        sector.filter = self._filters[group]
        sector_shape = sector._shape
        # Chipmunk's structs, passed and read as they are (quicker than pymunk's tuples, field by field)
        shape_filter = ffi.new("cpShapeFilter *", tuple(sector.filter))[0]  # (owns its memory)
        hit, nearest = ffi.new("cpSegmentQueryInfo *"), ffi.new("cpPointQueryInfo *")
        corners = ffi.new("cpVect[5]")  # the polygon's, written in place
        hit_bytes, nearest_bytes, corner_bytes = ffi.buffer(hit), ffi.buffer(nearest), ffi.buffer(corners)

        def cone(x: float, y: float, direction: float, half_rad: float, max_cm: float) -> float | None:
            if half_rad > CONE_PART_RAD:  # a polygon round a wide sector would not be convex: ask in parts
                parts = math.ceil(half_rad / CONE_PART_RAD)
                part = half_rad / parts
                found = [
                    d
                    for i in range(parts)
                    if (d := cone(x, y, direction - half_rad + (2 * i + 1) * part, part, max_cm)) is not None
                ]
                return min(found) if found else None
            fx, fy = _cos(direction), _sin(direction)
            ch, sh = _cos(half_rad), _sin(half_rad)
            ax, ay = fx * ch + fy * sh, fy * ch - fx * sh  # the edge at direction - half_rad
            bx, by = fx * ch - fy * sh, fy * ch + fx * sh  # the edge at direction + half_rad
            apex = (x, y)
            best = max_cm
            # Each edge's first hit.  Its shape's nearest point may lie in the cone, unless the face hit
            # turns away from the apex into the cone (that point lies beyond the edge then): a guess that
            # saves a query, never a wrong answer (a shape reaching into the cone meets the polygon below).
            first = _segment_first(space, apex, (x + best * ax, y + best * ay), 0.0, shape_filter, hit)
            if first != _NULL:
                gx, gy, alpha = _unpack_hit(hit_bytes, _HIT_AT)  # (the face's normal, back at the apex)
                best *= alpha
                if gx * fx + gy * fy > -ch and gx * ax + gy * ay < gx * bx + gy * by:
                    first = _NULL
            second = _segment_first(space, apex, (x + best * bx, y + best * by), 0.0, shape_filter, hit)
            if second != _NULL:
                gx, gy, alpha = _unpack_hit(hit_bytes, _HIT_AT)
                best *= alpha
                if gx * fx + gy * fy > -ch and gx * bx + gy * by < gx * ax + gy * ay:
                    second = _NULL
            found = best < max_cm
            if best <= CONE_GAP_CM:
                return best
            # the nearest points of the shapes met, unless the guess above says they lie beyond the edges
            toward = None  # the direction of the nearest point found in the cone, if one is
            if first != _NULL and _shape_nearest(first, apex, nearest) < best:
                px, py = _unpack_point(nearest_bytes, _POINT_AT)
                px, py = px - x, py - y
                length = _sqrt(px * px + py * py)
                if px * fx + py * fy >= ch * length and length > CONE_GAP_CM:  # in the cone
                    best, toward = length, (px, py)
            if second != _NULL and second != first and _shape_nearest(second, apex, nearest) < best:
                px, py = _unpack_point(nearest_bytes, _POINT_AT)
                px, py = px - x, py - y
                length = _sqrt(px * px + py * py)
                if px * fx + py * fy >= ch * length and length > CONE_GAP_CM:
                    best, toward = length, (px, py)
            # A polygon round the sector of radius r, made of tangents to its arc: at the edges' ends, and
            # at the nearest point found (two tangents at u and n meet at r (u + n) / (1 + u.n)), else at
            # the axis.  The shapes met above lie beyond these tangents: only another shape can reach in.
            r = best - CONE_GAP_CM
            if toward is not None:
                nx, ny = toward[0] / best, toward[1] / best
                an, bn = nx * ax + ny * ay, nx * bx + ny * by
                if an > 1.0 - 1e-12 or bn > 1.0 - 1e-12:  # on an edge: its tangent is the edge's own
                    toward = None
            if toward is None:  # a kite: the edges' tangents meet on the axis, r / cos(half_rad) away
                k = r / ch
                _pack_four(
                    corner_bytes, 0, x, y, x + r * ax, y + r * ay, x + k * fx, y + k * fy, x + r * bx, y + r * by
                )  # fmt: skip
                _set_corners(sector_shape, 4, corners)
            else:
                ka, kb = r / (1.0 + an), r / (1.0 + bn)
                _pack_five(
                    corner_bytes, 0, x, y, x + r * ax, y + r * ay, x + ka * (ax + nx), y + ka * (ay + ny),
                    x + kb * (bx + nx), y + kb * (by + ny), x + r * bx, y + r * by,
                )  # fmt: skip
                _set_corners(sector_shape, 5, corners)
            if _anything_in(space, sector_shape, _NULL, _NULL):
                for met in shape_query(sector):
                    d = _shape_nearest(met.shape._shape, apex, nearest)
                    if d < best:
                        px, py = _unpack_point(nearest_bytes, _POINT_AT)
                        px, py = px - x, py - y
                        if d <= 0.0 or px * fx + py * fy >= ch * _sqrt(px * px + py * py):
                            best, found = max(d, 0.0), True
            return best if found else None

        return cone

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
        return bool(_anything_in(self._cp_space, probe._shape, _NULL, _NULL))  # (no shape is a sensor)

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
