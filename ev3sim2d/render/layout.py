"""Where things go in a frame: the map (world cm to pixels) on the left, the brick's panel on the right."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

DEFAULT_SIZE = (1280, 720)
"""A frame's width and height in px, unless a caller (--size) says otherwise."""

SHIFT = 4
"""OpenCV draws with coordinates in 1/16 px (shift=4), so that slow motion moves smoothly."""
ONE = 1 << SHIFT

PANEL_SHARE = 0.33  # of the frame's width, in a video frame ...
SMALL_PANEL_SHARE = 0.38  # ... and in one less than SMALL_WIDTH px wide, so the text can stay larger
SMALL_WIDTH = 1000
MAP_PAD_SHARE = 0.015  # of the frame's height, around the world


@dataclass(frozen=True)
class MapView:
    """World cm to frame px: x_px = left + x·scale, y_px = bottom − y·scale (y points up in the world)."""

    scale: float  # px per cm
    left: float
    bottom: float
    world_cm: tuple[float, float]

    def px(self, x_cm: float, y_cm: float) -> tuple[int, int]:
        """The pixel of a world point."""
        return int(round(self.left + x_cm * self.scale)), int(round(self.bottom - y_cm * self.scale))

    def fixed(self, points_cm) -> np.ndarray:
        """World points (n × 2, cm) as OpenCV fixed-point pixel coordinates (use with shift=SHIFT)."""
        p = np.asarray(points_cm, dtype=float).reshape(-1, 2)
        s = self.scale * ONE
        return np.rint(p * (s, -s) + (self.left * ONE, self.bottom * ONE)).astype(np.int32)

    def length(self, cm: float) -> int:
        """A length in whole px, at least 1."""
        return max(1, int(round(cm * self.scale)))

    @property
    def box(self) -> tuple[int, int, int, int]:
        """The world's rectangle in px: x0, y0 (top), x1, y1 (bottom), exclusive ends."""
        x0, y1 = self.px(0, 0)
        x1, y0 = self.px(*self.world_cm)
        return x0, y0, x1, y1


@dataclass(frozen=True)
class FrameLayout:
    """A frame's size, its map view and, in video frames, the side panel from `panel_x` to the right edge."""

    width: int
    height: int
    panel_x: int  # == width when there is no panel
    view: MapView
    font_px: int

    @property
    def has_panel(self) -> bool:
        return self.panel_x < self.width

    @classmethod
    def video(cls, world_cm: tuple[float, float], width: int, height: int) -> FrameLayout:
        """Map on the left, panel on the right third."""
        panel_w = int(round(width * (PANEL_SHARE if width >= SMALL_WIDTH else SMALL_PANEL_SHARE)))
        map_w = width - panel_w
        pad = max(2, int(round(height * MAP_PAD_SHARE)))
        view = _fit(world_cm, 0, 0, map_w, height, pad)
        font_px = max(9, int(round(min(height / 48, panel_w / 28))))
        return cls(width, height, map_w, view, font_px)

    @classmethod
    def picture(cls, world_cm: tuple[float, float], width: int, caption_lines: int = 0) -> FrameLayout:
        """The world alone, `width` px wide, its height from the world's shape, room for caption lines below."""
        pad = max(2, int(round(width * 0.012)))
        font_px = max(9, int(round(width / 64)))
        scale = (width - 2 * pad) / world_cm[0]
        map_h = int(round(world_cm[1] * scale)) + 2 * pad
        caption_h = int(round(caption_lines * font_px * 1.45)) + (pad if caption_lines else 0)
        height = map_h + caption_h
        height += height % 2
        view = _fit(world_cm, 0, 0, width, map_h, pad)
        return cls(width, height, width, view, font_px)


def _fit(world_cm: tuple[float, float], x: int, y: int, w: int, h: int, pad: int) -> MapView:
    """The largest view of the world that fits in the box (x, y, w, h) less `pad`, centred."""
    scale = min((w - 2 * pad) / world_cm[0], (h - 2 * pad) / world_cm[1])
    left = x + (w - world_cm[0] * scale) / 2
    bottom = y + (h + world_cm[1] * scale) / 2
    return MapView(scale, round(left), round(bottom), world_cm)
