"""EV3 colour sensor facing down: reflected light, colour, ambient and raw values of the floor.

The sensor sees a small square spot (`spot_cm`, default 1.5 cm) and reports the
area-weighted mean of the cells under it, so its reading changes smoothly
across the edge of a line, as a real sensor's does and proportional line
following needs.  Reflected light per shade and colour: see world/colors.py
(black tape about 5, white paper about 75).
"""

from __future__ import annotations

import math

from .sensor import LegoSensor, Mode

DEFAULT_SPOT_CM = 1.5


class ColorSensor(LegoSensor):
    DRIVER = "lego-ev3-color"
    MODES = {
        "COL-REFLECT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-AMBIENT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-COLOR": Mode(1, 0, "col", "s8", 0, 7),
        "REF-RAW": Mode(2, 0, "", "s16", 0, 1023),
        "RGB-RAW": Mode(3, 0, "", "s16", 0, 1023),
        "COL-CAL": Mode(4, 0, "", "u16", 0, 65535),
    }

    def __init__(self, address, spec, surroundings, floor, ambient: float = 10.0) -> None:
        super().__init__(address, spec, surroundings)
        self.floor = floor
        self.ambient = ambient
        self.half = float(spec.options.get("spot_cm", DEFAULT_SPOT_CM)) / 2.0

    def _cells(self) -> list[tuple[int, int, float]]:
        """(col, row, share of the spot) for the cells under the spot."""
        x, y, _ = self.position()
        floor, h = self.floor, self.half
        size = floor.cell_cm
        area = (2 * h) ** 2
        cells = []
        x0, x1, y0, y1 = x - h, x + h, y - h, y + h
        for col in range(
            max(int(math.floor(x0 / size)), 0), min(int(math.floor(x1 / size)), floor.width - 1) + 1
        ):
            wx = min(x1, (col + 1) * size) - max(x0, col * size)
            if wx <= 0:
                continue
            for row in range(
                max(int(math.floor(y0 / size)), 0), min(int(math.floor(y1 / size)), floor.height - 1) + 1
            ):
                wy = min(y1, (row + 1) * size) - max(y0, row * size)
                if wy > 0:
                    cells.append((col, row, wx * wy / area))
        return cells

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "COL-AMBIENT":
            return (self.ambient,)
        cells = self._cells()
        if mode == "COL-REFLECT":
            table = self.floor.reflected
            return (sum(table[row][col] * share for col, row, share in cells),)
        if mode == "COL-COLOR":
            col, row, _ = max(cells, key=lambda c: c[2])
            return (self.floor.color_id[row][col],)
        table = self.floor.raw_rgb
        rgb = [sum(table[row][col][i] * share for col, row, share in cells) for i in range(3)]
        if mode == "RGB-RAW":
            return tuple(rgb)
        if mode == "REF-RAW":
            return (rgb[0], 0.8 * rgb[0])
        return (rgb[0], rgb[1], rgb[2], 0)
