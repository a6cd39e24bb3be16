"""The still part of every frame, drawn once: floor shades and colours, the cell grid, walls, regions."""

from __future__ import annotations

import math

import cv2
import numpy as np

from ..world.world import World
from . import palette
from .layout import MapView
from .text import Font, draw_label

MIN_CELL_PX_FOR_LINES = 6  # cells smaller than this get no grid lines
WALL_HATCH_PX = 7  # distance between the diagonal lines on walls
WALL_HATCH_LIGHTEN = 28


def draw_world(image: np.ndarray, world: World, view: MapView, label_font: Font | None = None) -> None:
    """Paint the world into `image` (already filled with the surround) where `view` puts it."""
    grid = world.grid
    bx0, by0, bx1, by1 = view.box
    x0, y0 = max(bx0, 0), max(by0, 0)
    x1, y1 = min(bx1, image.shape[1]), min(by1, image.shape[0])
    cell_px = grid.cell_cm * view.scale
    # the cell under the middle of every pixel
    cols = np.clip(((np.arange(x0, x1) + 0.5 - view.left) // cell_px).astype(int), 0, grid.width - 1)
    rows = np.clip(((view.bottom - np.arange(y0, y1) - 0.5) // cell_px).astype(int), 0, grid.height - 1)
    colors = np.array(grid.display_rgb_rows(), dtype=np.uint8)[:, :, ::-1]
    walls = np.array(grid.wall_rows(), dtype=bool)
    area = image[y0:y1, x0:x1]
    area[:] = colors[rows[:, None], cols[None, :]]
    wall_px = walls[rows[:, None], cols[None, :]]

    if cell_px >= MIN_CELL_PX_FOR_LINES:
        col_edge = np.diff(cols, prepend=cols[0]) != 0
        row_edge = np.diff(rows, prepend=rows[0]) != 0
        lines = (col_edge[None, :] | row_edge[:, None]) & ~wall_px
        area[lines] = (area[lines] * palette.GRID_LINE_DARKEN).astype(np.uint8)

    # walls are hatched, so that they never look like dark floor, and get a light edge
    ys, xs = np.ogrid[y0:y1, x0:x1]
    hatch = wall_px & ((xs + ys) % WALL_HATCH_PX == 0)
    area[hatch] = np.minimum(area[hatch].astype(int) + WALL_HATCH_LIGHTEN, 255).astype(np.uint8)
    contours, _ = cv2.findContours(wall_px.astype(np.uint8), cv2.RETR_LIST, cv2.CHAIN_APPROX_SIMPLE)
    cv2.drawContours(area, contours, -1, palette.WALL_EDGE, 1, cv2.LINE_8)

    for region in world.regions.values():
        _draw_region(image, view, region, label_font)


def _draw_region(image: np.ndarray, view: MapView, region, font: Font | None) -> None:
    """A dashed outline round the region, and its name at its top-left corner."""
    mask = np.zeros(image.shape[:2], dtype=np.uint8)
    for x0, y0, x1, y1 in region.rects:
        px0, py1 = view.px(x0, y0)
        px1, py0 = view.px(x1, y1)
        mask[max(py0, 0) : max(py1, 0), max(px0, 0) : max(px1, 0)] = 1
    contours, _ = cv2.findContours(mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    thickness = max(1, int(round(view.scale * 0.35)))
    dash = max(4.0, view.scale * 2.0)
    for contour in contours:
        draw_dashed(image, contour.reshape(-1, 2).astype(float), palette.REGION, thickness, dash)
    if font is not None and contours:
        x, y, w, h = cv2.boundingRect(np.vstack(contours))
        if w > font.width(region.name) // 2 and h > font.height:
            draw_label(
                image,
                font,
                region.name,
                x + thickness + 1,
                y + thickness + 1,
                palette.REGION,
                palette.LABEL_BG,
                pad=1,
            )


def draw_dashed(
    image: np.ndarray, points: np.ndarray, color, thickness: int, dash: float, closed: bool = True
) -> None:
    """A dashed polyline through `points` (px): dashes and gaps of `dash` px, continuing round corners."""
    if closed:
        points = np.vstack([points, points[:1]])
    on, left = True, dash
    for (ax, ay), (bx, by) in zip(points[:-1], points[1:], strict=True):
        length = math.hypot(bx - ax, by - ay)
        pos = 0.0
        while pos < length:
            step = min(left, length - pos)
            if on:
                p = (int(round(ax + (bx - ax) * pos / length)), int(round(ay + (by - ay) * pos / length)))
                q = (
                    int(round(ax + (bx - ax) * (pos + step) / length)),
                    int(round(ay + (by - ay) * (pos + step) / length)),
                )
                cv2.line(image, p, q, color, thickness, cv2.LINE_AA)
            pos += step
            left -= step
            if left <= 1e-9:
                on, left = not on, dash
