"""The world's walls as the renderer asks about them: where a beam stops, where a robot touches."""

from __future__ import annotations

import math

import numpy as np


class Walls:
    """Axis-aligned wall rectangles (x0, y0, x1, y1) in cm."""

    def __init__(self, rects) -> None:
        self.rects = np.asarray(list(rects), dtype=float).reshape(-1, 4)

    def ray(self, x: float, y: float, direction_rad: float, max_cm: float) -> float:
        """Distance along the ray to the first wall (slab method), or max_cm if none is nearer."""
        if not len(self.rects):
            return max_cm
        dx, dy = math.cos(direction_rad), math.sin(direction_rad)
        r = self.rects
        with np.errstate(divide="ignore", invalid="ignore"):
            tx0, tx1 = (r[:, 0] - x) / dx, (r[:, 2] - x) / dx
            ty0, ty1 = (r[:, 1] - y) / dy, (r[:, 3] - y) / dy
        if dx == 0:
            inside = (r[:, 0] <= x) & (x <= r[:, 2])
            tx0 = np.where(inside, -np.inf, np.inf)  # outside the slab: never entered
            tx1 = np.full(len(r), np.inf)
        if dy == 0:
            inside = (r[:, 1] <= y) & (y <= r[:, 3])
            ty0 = np.where(inside, -np.inf, np.inf)
            ty1 = np.full(len(r), np.inf)
        near = np.maximum(np.minimum(tx0, tx1), np.minimum(ty0, ty1))
        far = np.minimum(np.maximum(tx0, tx1), np.maximum(ty0, ty1))
        hits = near[(near <= far) & (far >= 0)]
        if not len(hits):
            return max_cm
        return float(min(max(hits.min(), 0.0), max_cm))

    def nearest(self, points) -> tuple[float, tuple[float, float], tuple[float, float]]:
        """Of the points (n × 2, cm), the one nearest a wall: (distance, that point, the wall point nearest it)."""
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        if not len(self.rects) or not len(p):
            return (math.inf, (0.0, 0.0), (0.0, 0.0))
        r = self.rects
        cx = np.clip(p[:, 0, None], r[None, :, 0], r[None, :, 2])
        cy = np.clip(p[:, 1, None], r[None, :, 1], r[None, :, 3])
        d = np.hypot(cx - p[:, 0, None], cy - p[:, 1, None])
        i, j = np.unravel_index(int(np.argmin(d)), d.shape)
        return (float(d[i, j]), (float(p[i, 0]), float(p[i, 1])), (float(cx[i, j]), float(cy[i, j])))
