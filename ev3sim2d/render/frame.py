"""A plain top-down drawing of a run's last moment: the world, each robot's trail and body.

Reads only the trace (the world's YAML text is in it).  The full renderer,
with sensors, panel and video, builds on this later.
"""

from __future__ import annotations

import math
from pathlib import Path

import cv2
import numpy as np

from ..trace import Trace
from ..world.maze_file import parse_maze

ROBOT_COLORS = [(30, 170, 230), (200, 90, 30), (60, 160, 60), (150, 60, 160)]  # BGR


def world_image(grid, px_per_cm: float) -> np.ndarray:
    """The grid as a BGR image, row 0 at the bottom."""
    rgb = np.array(grid.display_rgb_rows(), dtype=np.uint8)[::-1]  # top row first
    cell_px = max(1, int(round(grid.cell_cm * px_per_cm)))
    image = np.repeat(np.repeat(rgb, cell_px, axis=0), cell_px, axis=1)[:, :, ::-1].copy()
    # faint cell lines
    image[::cell_px, :, :] = (image[::cell_px, :, :] * 0.9).astype(np.uint8)
    image[:, ::cell_px, :] = (image[:, ::cell_px, :] * 0.9).astype(np.uint8)
    return image


def draw_final_frame(trace: Trace, width_px: int = 800) -> np.ndarray:
    world = parse_maze(trace.world["text"], trace.world.get("name", "<trace>"))
    grid = world.grid
    cell_px = max(1, int(round(width_px / grid.width)))
    px_per_cm = cell_px / grid.cell_cm
    image = world_image(grid, px_per_cm)
    height = image.shape[0]

    def to_px(x: float, y: float) -> tuple[int, int]:
        return int(round(x * px_per_cm)), int(round(height - y * px_per_cm))

    for i, robot in enumerate(trace.robots):
        color = ROBOT_COLORS[i % len(ROBOT_COLORS)]
        poses = trace.poses(i)
        points = np.array([to_px(x, y) for x, y, _ in poses[:: max(1, len(poses) // 2000)]], dtype=np.int32)
        if len(points) > 1:
            cv2.polylines(image, [points], False, color, max(1, int(px_per_cm * 0.4)), cv2.LINE_AA)
        x, y, heading = poses[-1]
        body = robot.get("body") or {"front_cm": 9, "back_cm": 9, "width_cm": 13}
        h = math.radians(heading)
        corners = [
            (body["front_cm"], body["width_cm"] / 2),
            (-body["back_cm"], body["width_cm"] / 2),
            (-body["back_cm"], -body["width_cm"] / 2),
            (body["front_cm"], -body["width_cm"] / 2),
        ]
        outline = np.array(
            [
                to_px(x + cx * math.cos(h) - cy * math.sin(h), y + cx * math.sin(h) + cy * math.cos(h))
                for cx, cy in corners
            ],
            dtype=np.int32,
        )
        cv2.fillPoly(image, [outline], color, cv2.LINE_AA)
        cv2.polylines(image, [outline], True, (40, 40, 40), 1, cv2.LINE_AA)
        tip = to_px(x + body["front_cm"] * math.cos(h), y + body["front_cm"] * math.sin(h))
        cv2.line(image, to_px(x, y), tip, (20, 20, 20), max(1, int(px_per_cm * 0.5)), cv2.LINE_AA)
    return image


def write_png(trace: Trace, path: str | Path, width_px: int = 800) -> None:
    if not cv2.imwrite(str(path), draw_final_frame(trace, width_px)):
        raise OSError(f"could not write {path}")
