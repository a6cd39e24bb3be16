"""Questions about the floor plan that checks ask: how far is the wall ahead, how far is the line."""

from __future__ import annotations

import math

import numpy as np

from ..world.grid import Grid

RAY_STEP_CM = 0.05


def distance_to_wall(
    grid: Grid, x_cm: float, y_cm: float, heading_deg: float, max_cm: float = 500.0
) -> float:
    """Distance from (x, y) straight along the heading to the first wall cell (max_cm if none)."""
    dx, dy = math.cos(math.radians(heading_deg)), math.sin(math.radians(heading_deg))
    walls = grid.wall_rows()
    s = grid.cell_cm
    steps = int(max_cm / RAY_STEP_CM)
    for i in range(steps + 1):
        d = i * RAY_STEP_CM
        col, row = math.floor((x_cm + d * dx) / s), math.floor((y_cm + d * dy) / s)
        if not (0 <= row < grid.height and 0 <= col < grid.width) or walls[row][col]:
            return d
    return max_cm


def line_cells(grid: Grid, darker_than: float) -> np.ndarray:
    """[row, col] booleans: floor cells whose reflected light is below `darker_than` (the line)."""
    reflected = np.array(grid.reflected_rows(), dtype=float)
    walls = np.array(grid.wall_rows(), dtype=bool)
    return (reflected < darker_than) & ~walls


def distance_to_cells(grid: Grid, cells: np.ndarray, xy: np.ndarray, reach_cm: float) -> np.ndarray:
    """Distance from each point to the nearest marked cell, exact up to reach_cm (beyond: reach_cm + something)."""
    s = grid.cell_cm
    k = int(math.ceil(reach_cm / s))
    col = np.floor(xy[:, 0] / s).astype(int)
    row = np.floor(xy[:, 1] / s).astype(int)
    best = np.full(len(xy), np.inf)
    height, width = cells.shape
    for dr in range(-k, k + 1):
        for dc in range(-k, k + 1):
            c, r = col + dc, row + dr
            inside = (c >= 0) & (c < width) & (r >= 0) & (r < height)
            marked = np.zeros(len(xy), dtype=bool)
            marked[inside] = cells[r[inside], c[inside]]
            if not marked.any():
                continue
            x0, y0 = c * s, r * s
            ddx = np.maximum.reduce([x0 - xy[:, 0], np.zeros(len(xy)), xy[:, 0] - (x0 + s)])
            ddy = np.maximum.reduce([y0 - xy[:, 1], np.zeros(len(xy)), xy[:, 1] - (y0 + s)])
            best = np.where(marked, np.minimum(best, np.hypot(ddx, ddy)), best)
    return best
