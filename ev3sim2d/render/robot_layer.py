"""A robot drawn to scale at one moment: body, wheels, heading, its sensors where they sit, what they sense.

The ultrasonic (and infrared) beam is drawn as its cone up to the measured
distance, with the point it hit and the distance; the colour sensor as the
spot of floor it sees; a robot touching a wall gets a burst where it touches.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import cv2
import numpy as np

from ..devices.registry import SENSORS, DeviceKindError, sensor_class
from ..devices.sensor import LegoSensor
from ..world.robot_spec import DEFAULT_ROBOT_COLOR
from . import palette
from .layout import SHIFT, MapView
from .text import Font, blend_mask, draw_label
from .walls import Walls

TYRE_WIDTH_CM = 2.8  # the driving base's 56 × 28 mm tyres
BEAM_ALPHA = 0.28
TRAIL_RECENT_S = 3.0  # the trail fades in over this much simulated time
RECENT_TRAIL_POINTS = 60  # the recent trail is drawn through at most about this many points
TRAIL_TINT = 0.45  # share of the robot colour in the old trail (the rest white)
CONTACT_REACH_CM = 1.5  # a wall this close to the body is where it touches
ARROW_BACK_CM = 1.5  # the heading arrow reaches this far behind the axle
# a robot's number sits on a disc at least this share of the picture's height in radius (10 px in a
# 720 px frame), and at least this many px, to stay readable however small the robot is drawn
NUMBER_MIN_RADIUS_SHARE = 1 / 72
NUMBER_MIN_RADIUS_PX = 6

# where a sensor sits when an old trace does not say: angle_deg, radius_cm, facing
_DEFAULT_MOUNTS = {
    "touch": (0.0, 9.0, "forward"),
    "gyro": (180.0, 3.0, "down"),
    "color": (0.0, 7.0, "down"),
    "ultrasonic": (0.0, 8.0, "forward"),
    "infrared": (0.0, 8.0, "forward"),
}


def sensor_device(kind: str) -> type[LegoSensor]:
    """The device class that says how a sensor of `kind` is drawn (devices/sensor.py: LABEL, HOUSING,
    FLOOR_SPOT, beam_cm); a kind this ev3sim2d does not know (a trace from a plug-in that is not installed
    here) is drawn as any sensor: a small box, its mode and values in the panel."""
    return SENSORS.get(kind) or _plugin_device(kind)


@functools.cache
def _plugin_device(kind: str) -> type[LegoSensor]:
    """A kind not registered yet: an installed plug-in's, else the base (looked for once per kind)."""
    try:
        found = sensor_class(kind)
    except DeviceKindError:
        found = None
    return found if found is not None else LegoSensor


@dataclass(frozen=True)
class SensorLook:
    """Where a sensor sits on the robot and what it sees (robot frame: x forward, y left, cm)."""

    port: str
    kind: str
    angle_deg: float
    radius_cm: float
    facing: str
    aim_deg: float = 0.0
    spot_cm: float = 1.5
    cone_deg: float = 15.0
    max_cm: float = 255.0

    @property
    def offset_cm(self) -> tuple[float, float]:
        a = math.radians(self.angle_deg)
        return (self.radius_cm * math.cos(a), self.radius_cm * math.sin(a))

    def pose(self, x: float, y: float, heading_deg: float) -> tuple[float, float, float]:
        """The sensor's x, y (cm) and the direction it looks (radians) for a robot at x, y, heading."""
        h = math.radians(heading_deg)
        a = h + math.radians(self.angle_deg)
        return (
            x + self.radius_cm * math.cos(a),
            y + self.radius_cm * math.sin(a),
            h + math.radians(self.aim_deg),
        )


@dataclass(frozen=True)
class RobotLook:
    """What the trace says a robot looks like."""

    name: str
    color: tuple[int, int, int]  # BGR
    front_cm: float
    back_cm: float
    width_cm: float
    wheel_diameter_cm: float
    axle_track_cm: float
    sensors: tuple[SensorLook, ...]

    @property
    def trail_color(self) -> tuple[int, int, int]:
        return tuple(int(c * TRAIL_TINT + 255 * (1 - TRAIL_TINT)) for c in self.color)


def robot_looks(descriptions: list[dict]) -> list[RobotLook]:
    """One RobotLook per robot of a trace, in its robot file's colour unless that looks like an earlier one's."""
    colors = robot_colors([tuple(d.get("color") or DEFAULT_ROBOT_COLOR) for d in descriptions])
    looks = []
    for i, (d, rgb) in enumerate(zip(descriptions, colors, strict=True)):
        body = d.get("body") or {"front_cm": 9.0, "back_cm": 7.0, "width_cm": 15.0}
        mounts = {m["port"]: m for m in d.get("sensor_mounts", [])}
        sensors = []
        for port, kind in d.get("sensors", []):
            m = mounts.get(port)
            if m is None:
                angle, radius, facing = _DEFAULT_MOUNTS.get(kind, (0.0, 0.0, "down"))
                m = {"angle_deg": angle, "radius_cm": radius, "facing": facing}
            sensors.append(
                SensorLook(
                    port,
                    kind,
                    float(m.get("angle_deg", 0.0)),
                    float(m.get("radius_cm", 0.0)),
                    m.get("facing", "forward"),
                    float(m.get("aim_deg", 0.0)),
                    float(m.get("spot_cm", 1.5)),
                    float(m.get("cone_deg", _option_default(kind, "cone_deg", 15.0))),
                    float(m.get("max_cm", _option_default(kind, "max_cm", 255.0))),
                )
            )
        looks.append(
            RobotLook(
                d.get("name", f"robot{i + 1}"),
                palette.bgr(rgb),
                float(body["front_cm"]),
                float(body["back_cm"]),
                float(body["width_cm"]),
                float(d.get("wheel_diameter_mm", 56)) / 10,
                float(d.get("axle_track_mm", 120)) / 10,
                tuple(sensors),
            )
        )
    return looks


def _option_default(kind: str, option: str, otherwise: float) -> float:
    """The default of a robot-file option of a sensor kind (an old trace does not record it)."""
    default = sensor_device(kind).OPTIONS.get(option)
    return default[0] if default is not None else otherwise


def robot_colors(own: list[tuple[int, int, int]]) -> list[tuple[int, int, int]]:
    """The (r, g, b) each robot is drawn in: its own colour when no earlier robot's looks like it, else the
    first of the palette's robot colours that looks like no robot's (so that no two robots look alike)."""
    kept: list[tuple[int, int, int] | None] = []
    for rgb in own:
        alike = any(k is not None and palette.looks_alike(rgb, k) for k in kept)
        kept.append(None if alike else tuple(int(c) for c in rgb))
    taken = [k for k in kept if k is not None]
    colors = []
    for i, rgb in enumerate(kept):
        if rgb is None:
            free = [c for c in palette.ROBOT_COLORS if not any(palette.looks_alike(c, t) for t in taken)]
            rgb = free[0] if free else palette.ROBOT_COLORS[i % len(palette.ROBOT_COLORS)]
            taken.append(rgb)
        colors.append(rgb)
    return colors


def beam_distance_cm(sensor: SensorLook, reading: tuple[str, list[int]] | None) -> float | None:
    """How far the beam reaches by the sensor's last reading, or None if it has no distance reading."""
    if reading is None:
        return None
    mode, values = reading
    if not values:
        return None
    return sensor_device(sensor.kind).beam_cm(mode, values, sensor.max_cm)


def _to_world(points, x: float, y: float, heading_deg: float) -> np.ndarray:
    """Robot-frame points (cm) placed at the robot's pose."""
    p = np.asarray(points, dtype=float).reshape(-1, 2)
    h = math.radians(heading_deg)
    c, s = math.cos(h), math.sin(h)
    return np.column_stack([x + p[:, 0] * c - p[:, 1] * s, y + p[:, 0] * s + p[:, 1] * c])


def _box(x0: float, y0: float, x1: float, y1: float) -> list[tuple[float, float]]:
    return [(x1, y1), (x0, y1), (x0, y0), (x1, y0)]


def body_points(look: RobotLook, samples_per_side: int = 4) -> np.ndarray:
    """Points round the body outline, robot frame."""
    corners = _box(-look.back_cm, -look.width_cm / 2, look.front_cm, look.width_cm / 2)
    points = []
    for (ax, ay), (bx, by) in zip(corners, corners[1:] + corners[:1], strict=True):
        for k in range(samples_per_side):
            f = k / samples_per_side
            points.append((ax + (bx - ax) * f, ay + (by - ay) * f))
    return np.array(points)


def contact_point(
    look: RobotLook, pose: tuple[float, float, float], walls: Walls
) -> tuple[float, float] | None:
    """Where the robot at `pose` touches a wall (the wall point nearest its body), or None if no wall is near."""
    distance, _, wall_point = walls.nearest(_to_world(body_points(look), *pose))
    return wall_point if distance <= CONTACT_REACH_CM else None


def draw_beam(
    image: np.ndarray,
    view: MapView,
    font: Font,
    sensor: SensorLook,
    pose: tuple[float, float, float],
    distance_cm: float,
    walls: Walls,
    bounds: tuple[int, int, int, int] | None = None,
) -> None:
    """The sensor's cone up to the measured distance, the point it hit and the distance (label kept in `bounds`)."""
    sx, sy, facing = sensor.pose(*pose)
    half = math.radians(sensor.cone_deg) / 2
    nothing = distance_cm >= sensor.max_cm - 0.05
    reach = distance_cm
    arc = [
        (sx + reach * math.cos(facing + a), sy + reach * math.sin(facing + a))
        for a in np.linspace(-half, half, 7)
    ]
    polygon = view.fixed([(sx, sy), *arc])
    _blend_polygon(image, polygon, palette.BEAM, BEAM_ALPHA * (0.5 if nothing else 1.0))
    if nothing:
        return
    # which of the sensor's three rays found this distance: the hit is on that one
    best, direction = math.inf, facing
    for offset in (0.0, -half, half):
        gap = abs(walls.ray(sx, sy, facing + offset, sensor.max_cm) - distance_cm)
        if gap < best:
            best, direction = gap, facing + offset
    if best > 1.0:
        direction = facing  # another robot, most likely: show it on the axis
    hx, hy = sx + distance_cm * math.cos(direction), sy + distance_cm * math.sin(direction)
    start, hit = view.fixed([(sx, sy), (hx, hy)])
    cv2.line(image, tuple(start), tuple(hit), palette.BEAM, 1, cv2.LINE_AA, SHIFT)
    radius = max(3, view.length(1.2))
    cv2.circle(image, tuple(hit), radius << SHIFT, palette.LABEL_BG, -1, cv2.LINE_AA, SHIFT)
    cv2.circle(image, tuple(hit), (radius - 1) << SHIFT, palette.HIT, -1, cv2.LINE_AA, SHIFT)
    label = (
        f"≈{distance_cm:.0f} cm" if sensor_device(sensor.kind).BEAM_APPROXIMATE else f"{distance_cm:.1f} cm"
    )
    px, py = hit[0] >> SHIFT, hit[1] >> SHIFT
    # put the label beyond the hit point, away from the robot
    ux, uy = math.cos(direction), -math.sin(direction)
    lx = px + int(ux * (radius + 4)) - (0 if ux >= 0 else font.width(label) + 4)
    ly = py + int(uy * (radius + 4)) - (font.height + 4 if uy < 0 else 0)
    draw_label(image, font, label, lx, ly, palette.LABEL_FG, palette.LABEL_BG, bounds=bounds)


def _blend_polygon(image: np.ndarray, polygon: np.ndarray, color, alpha: float) -> None:
    """Fill a polygon (fixed-point px) with `color` at opacity `alpha`, touching only its bounding box."""
    x, y, w, h = cv2.boundingRect(polygon >> SHIFT)
    x0, y0 = max(x - 1, 0), max(y - 1, 0)
    x1, y1 = min(x + w + 2, image.shape[1]), min(y + h + 2, image.shape[0])
    if x0 >= x1 or y0 >= y1:
        return
    roi = image[y0:y1, x0:x1]
    painted = roi.copy()
    cv2.fillPoly(
        painted, [polygon - np.array([x0 << SHIFT, y0 << SHIFT], dtype=np.int32)], color, cv2.LINE_AA, SHIFT
    )
    cv2.addWeighted(painted, alpha, roi, 1.0 - alpha, 0.0, dst=roi)


@functools.lru_cache(maxsize=64)
def _robot_parts(look: RobotLook) -> tuple[np.ndarray, tuple[tuple[str, str, int, int], ...]]:
    """The robot's drawing in its own frame: all points in one array, and (part, port, first, end) rows."""
    points: list[tuple[float, float]] = []
    parts: list[tuple[str, str, int, int]] = []

    def add(part: str, port: str, shape) -> None:
        parts.append((part, port, len(points), len(points) + len(shape)))
        points.extend(shape)

    half_w = look.width_cm / 2
    add("body", "", _box(-look.back_cm, -half_w, look.front_cm, half_w))
    r = look.wheel_diameter_cm / 2
    for side in (1, -1):
        inner = side * max(look.axle_track_cm / 2 - TYRE_WIDTH_CM / 2, 0)
        outer = side * min(look.axle_track_cm / 2 + TYRE_WIDTH_CM / 2, half_w)
        add("wheel", "", _box(-r, min(inner, outer), r, max(inner, outer)))
    for sensor in look.sensors:
        sx, sy = sensor.offset_cm
        aim = math.radians(sensor.aim_deg)
        housing = sensor_device(sensor.kind).HOUSING
        if housing == "bumper":
            add(
                "bumper",
                sensor.port,
                _rotated_box(sx - 0.6 * math.cos(aim), sy - 0.6 * math.sin(aim), 1.2, 4.0, aim),
            )
        elif housing == "eyes":
            add("housing", sensor.port, _rotated_box(sx - math.cos(aim), sy - math.sin(aim), 2.0, 5.0, aim))
            for eye in (-1.3, 1.3):
                add(
                    "eye",
                    sensor.port,
                    [
                        (
                            sx - 0.8 * math.cos(aim) - eye * math.sin(aim),
                            sy - 0.8 * math.sin(aim) + eye * math.cos(aim),
                        )
                    ],
                )
        else:
            add("housing", sensor.port, _box(sx - 1.0, sy - 1.0, sx + 1.0, sy + 1.0))
    add("arrow", "", [(4.0, 0.0), (-ARROW_BACK_CM, 2.6), (-0.3, 0.0), (-ARROW_BACK_CM, -2.6)])
    for sensor in look.sensors:
        if sensor_device(sensor.kind).FLOOR_SPOT and sensor.facing == "down":  # (facing forward: a wall)
            sx, sy = sensor.offset_cm
            h = sensor.spot_cm / 2
            add("spot", sensor.port, _box(sx - h, sy - h, sx + h, sy + h))
    return np.array(points, dtype=float), tuple(parts)


def draw_robot(
    image: np.ndarray,
    view: MapView,
    look: RobotLook,
    pose: tuple[float, float, float],
    touch_pressed: dict[str, bool] | None = None,
    touching: bool = False,
    number: int | None = None,
) -> None:
    """Body, wheels, sensors where they sit and a heading arrow at `pose`; a vermillion outline while touching;
    the robot's `number`, if given, upright on a disc behind the arrow."""
    touch_pressed = touch_pressed or {}
    points, parts = _robot_parts(look)
    fixed = view.fixed(_to_world(points, *pose))
    outline_px = max(1, view.length(0.35))
    eye_r = view.length(0.8) << SHIFT
    body = None
    for part, port, a, b in parts:
        shape = fixed[a:b]
        if part == "body":
            body = shape
            cv2.fillPoly(image, [shape], look.color, cv2.LINE_AA, SHIFT)
        elif part == "wheel":
            cv2.fillPoly(image, [shape], palette.WHEEL, cv2.LINE_AA, SHIFT)
        elif part == "bumper":
            color = palette.HIT if touch_pressed.get(port, False) else palette.SENSOR_BODY
            cv2.fillPoly(image, [shape], color, cv2.LINE_AA, SHIFT)
        elif part == "housing":
            cv2.fillPoly(image, [shape], palette.SENSOR_BODY, cv2.LINE_AA, SHIFT)
        elif part == "eye":
            cv2.circle(
                image, (int(shape[0, 0]), int(shape[0, 1])), eye_r, (200, 200, 200), -1, cv2.LINE_AA, SHIFT
            )
        elif part == "arrow":
            cv2.fillPoly(image, [shape], palette.OUTLINE, cv2.LINE_AA, SHIFT)
            edge = palette.CONTACT if touching else palette.OUTLINE
            cv2.polylines(image, [body], True, edge, outline_px * (2 if touching else 1), cv2.LINE_AA, SHIFT)
            if number is not None:
                _draw_number(image, view, look, pose, number)
        elif part == "spot":
            cv2.polylines(image, [shape], True, palette.LABEL_BG, max(2, outline_px) + 2, cv2.LINE_AA, SHIFT)
            cv2.polylines(image, [shape], True, palette.SPOT, max(2, outline_px), cv2.LINE_AA, SHIFT)


def _draw_number(
    image: np.ndarray, view: MapView, look: RobotLook, pose: tuple[float, float, float], number: int
) -> None:
    """The robot's number, dark on a white disc in the body's back half (behind the arrow), kept upright."""
    back = look.back_cm - ARROW_BACK_CM  # the body behind the arrow
    radius_cm = max(0.5, min(back / 2, look.width_cm / 3))
    ((cx, cy),) = view.fixed(_to_world([(-(look.back_cm + ARROW_BACK_CM) / 2, 0.0)], *pose))
    smallest = max(NUMBER_MIN_RADIUS_PX, int(round(image.shape[0] * NUMBER_MIN_RADIUS_SHARE)))
    radius = max(smallest, int(round(radius_cm * view.scale)))
    mask, (w, h) = _number_mask(str(number), radius)
    cv2.circle(image, (int(cx), int(cy)), radius << SHIFT, palette.LABEL_BG, -1, cv2.LINE_AA, SHIFT)
    cv2.circle(image, (int(cx), int(cy)), radius << SHIFT, palette.OUTLINE, 1, cv2.LINE_AA, SHIFT)
    x = int(round(cx / (1 << SHIFT) - w / 2))
    y = int(round(cy / (1 << SHIFT) - h / 2))
    blend_mask(image, mask, x, y, palette.LABEL_FG)


@functools.lru_cache(maxsize=32)
def _number_mask(text: str, radius_px: int) -> tuple[np.ndarray, tuple[int, int]]:
    """The coverage of `text` in bold digits that fill a disc of `radius_px`, cropped to its ink."""
    font = Font(max(8, int(round(radius_px * 1.45))), bold=True)
    mask = font.mask(text)
    rows, cols = np.nonzero(mask)
    mask = np.ascontiguousarray(mask[rows.min() : rows.max() + 1, cols.min() : cols.max() + 1])
    return mask, (mask.shape[1], mask.shape[0])


def _rotated_box(cx: float, cy: float, depth: float, width: float, aim: float) -> list[tuple[float, float]]:
    """A box `depth` long along the direction `aim` and `width` across, centred on (cx, cy)."""
    c, s = math.cos(aim), math.sin(aim)
    corners = _box(-depth / 2, -width / 2, depth / 2, width / 2)
    return [(cx + px * c - py * s, cy + px * s + py * c) for px, py in corners]


def draw_contact(image: np.ndarray, view: MapView, point: tuple[float, float], active: bool) -> None:
    """A burst where the robot touches a wall (active), or a small cross where it once did."""
    ((cx, cy),) = view.fixed([point])
    if active:
        r = view.length(2.2)
        cv2.circle(image, (int(cx), int(cy)), r << SHIFT, palette.CONTACT, max(2, r // 4), cv2.LINE_AA, SHIFT)
        for k in range(8):
            a = k * math.pi / 4
            p = (int(cx + math.cos(a) * r * 1.3 * 16), int(cy + math.sin(a) * r * 1.3 * 16))
            q = (int(cx + math.cos(a) * r * 1.9 * 16), int(cy + math.sin(a) * r * 1.9 * 16))
            cv2.line(image, p, q, palette.CONTACT, max(2, r // 5), cv2.LINE_AA, SHIFT)
    else:
        r = view.length(0.9) << SHIFT
        thickness = max(1, view.length(0.3))
        cv2.line(
            image,
            (int(cx - r), int(cy - r)),
            (int(cx + r), int(cy + r)),
            palette.CONTACT,
            thickness,
            cv2.LINE_AA,
            SHIFT,
        )
        cv2.line(
            image,
            (int(cx - r), int(cy + r)),
            (int(cx + r), int(cy - r)),
            palette.CONTACT,
            thickness,
            cv2.LINE_AA,
            SHIFT,
        )


def draw_trail(image: np.ndarray, view: MapView, points_cm: np.ndarray, color, thickness: int) -> None:
    """The path through the points as one anti-aliased line."""
    if len(points_cm) < 2:
        return
    cv2.polylines(image, [view.fixed(points_cm)], False, color, thickness, cv2.LINE_AA, SHIFT)


def draw_recent_trail(
    image: np.ndarray, view: MapView, look: RobotLook, points_cm: np.ndarray, thickness: int, pieces: int = 6
) -> None:
    """The last stretch of the path, fading from the old trail's tint into the robot's colour."""
    if len(points_cm) < 2:
        return
    step = max(1, len(points_cm) // RECENT_TRAIL_POINTS)
    if step > 1:  # every step-th point back from the newest, and the oldest, which meets the old trail
        points_cm = points_cm[np.unique(np.r_[0, np.arange(len(points_cm) - 1, -1, -step)])]
    fixed = view.fixed(points_cm)
    n = len(fixed)
    if n < 2:
        return
    old, new = np.array(look.trail_color, float), np.array(look.color, float)
    bounds = np.linspace(0, n - 1, pieces + 1).round().astype(int)
    for k in range(pieces):
        a, b = bounds[k], bounds[k + 1]
        if b <= a:
            continue
        f = (k + 1) / pieces
        color = tuple(int(v) for v in old + (new - old) * f)
        cv2.polylines(image, [fixed[a : b + 1]], False, color, thickness, cv2.LINE_AA, SHIFT)
