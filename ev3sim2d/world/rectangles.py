"""Merging a set of grid cells into a few axis-aligned rectangles (for wall bodies and regions).

Greedy: from each uncovered cell grow a run along one axis, then grow the run
along the other axis while every cell is still in the set.  Both orders are
tried and the one with fewer rectangles kept.  The rectangles never overlap
and cover exactly the given cells.
"""

from __future__ import annotations

from collections.abc import Iterable

CellSpan = tuple[int, int, int, int]
"""(col0, row0, col1, row1): the cells col0 <= col < col1, row0 <= row < row1."""

Rect = tuple[float, float, float, float]
"""(x0, y0, x1, y1) in cm, x0 < x1 and y0 < y1."""


def merge_cells(cells: Iterable[tuple[int, int]]) -> list[CellSpan]:
    """Cover the (col, row) cells exactly with few non-overlapping spans."""
    wanted = set(cells)
    if not wanted:
        return []
    along_rows = _grow(wanted)
    along_cols = [(r0, c0, r1, c1) for c0, r0, c1, r1 in _grow({(r, c) for c, r in wanted})]
    return along_cols if len(along_cols) < len(along_rows) else along_rows


def spans_to_rects(spans: Iterable[CellSpan], cell_cm: float) -> list[Rect]:
    """Cell spans as rectangles in cm."""
    s = float(cell_cm)
    return [(c0 * s, r0 * s, c1 * s, r1 * s) for c0, r0, c1, r1 in spans]


def _grow(wanted: set[tuple[int, int]]) -> list[CellSpan]:
    """Runs along the first coordinate, stacked along the second."""
    left = set(wanted)
    spans: list[CellSpan] = []
    for a, b in sorted(wanted, key=lambda ab: (ab[1], ab[0])):
        if (a, b) not in left:
            continue
        a1 = a + 1
        while (a1, b) in left:
            a1 += 1
        b1 = b + 1
        while all((i, b1) in left for i in range(a, a1)):
            b1 += 1
        for j in range(b, b1):
            for i in range(a, a1):
                left.discard((i, j))
        spans.append((a, b, a1, b1))
    return spans
