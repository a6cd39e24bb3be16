"""EV3 colour sensor facing down: reflected light, colour, ambient and raw values of the floor.

The sensor sees a small square spot (`spot_cm`, default 1.5 cm) and reports the
area-weighted mean of the cells under it, so its reading changes smoothly
across the edge of a line, as a real sensor's does and proportional line
following needs.  Reflected light per shade and colour: see world/colors.py
(black tape about 5, white paper about 75).
"""

from __future__ import annotations

from .sensor import LegoSensor, Mode

DEFAULT_SPOT_CM = 1.5


class ColorSensor(LegoSensor):
    DRIVER = "lego-ev3-color"
    MODES = {
        "COL-REFLECT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-AMBIENT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-COLOR": Mode(1, 0, "col", "s8", 0, 7, noisy=False),
        "REF-RAW": Mode(2, 0, "", "s16", 0, 1023),
        "RGB-RAW": Mode(3, 0, "", "s16", 0, 1023),
        "COL-CAL": Mode(4, 0, "", "u16", 0, 65535, noisy=False),
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
        return [
            (col, row, wx * wy)
            for col, wx in _overlaps(x - h, x + h, size, floor.width)
            for row, wy in _overlaps(y - h, y + h, size, floor.height)
        ]

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "COL-AMBIENT":
            return (self.ambient,)
        if mode == "COL-REFLECT":  # the line followers' mode: summed in place
            x, y, _ = self.position()
            floor, h = self.floor, self.half
            size = floor.cell_cm
            rows = _overlaps(y - h, y + h, size, floor.height)
            table = floor.reflected
            total = 0.0
            for col, wx in _overlaps(x - h, x + h, size, floor.width):  # the order and products of _cells
                for row, wy in rows:
                    total += table[row][col] * (wx * wy)
            return (total,)
        cells = self._cells()
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


def _overlaps(lo: float, hi: float, size: float, count: int) -> list[tuple[int, float]]:
    """The cells [i·size, (i+1)·size) that the interval [lo, hi] overlaps, with the share of it in each."""
    first, last = int(lo // size), int(hi // size)
    if first == last:
        return [(min(max(first, 0), count - 1), 1.0)]
    span = hi - lo
    if last == first + 1:  # the usual edge: the spot is smaller than a cell
        split = last * size
        return [(max(first, 0), (split - lo) / span), (min(last, count - 1), (hi - split) / span)]
    return [
        (min(max(i, 0), count - 1), (min(hi, (i + 1) * size) - max(lo, i * size)) / span)
        for i in range(first, last + 1)
    ]
