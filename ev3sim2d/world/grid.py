"""The floor plan of a world: a rectangle of square cells, each a wall or painted floor.

Cell (col, row) counts from the bottom-left, both from 0, and covers
x in [col*s, (col+1)*s), y in [row*s, (row+1)*s) cm, with s = `cell_cm`.
Text dumps list the top row first, as a world file does.  A Grid never
changes; `with_cell` gives a changed copy.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping, Sequence

from .cell import Cell
from .grid_text import read_text_grid, text_rows
from .legend import Legend, LegendEntry, as_legend
from .rectangles import Rect, merge_cells, spans_to_rects


class Grid:
    """Square cells in rows; row 0 is the bottom row."""

    __slots__ = ("_rows", "_cell_cm", "_legend", "_text", "_wall_rects")

    def __init__(
        self,
        rows: Sequence[Sequence[Cell]],
        cell_cm: float = 10.0,
        legend: Legend | None = None,
        *,
        text: str | None = None,
    ) -> None:
        """`rows[row][col]`, bottom row first; `legend` and `text` (the rows as written) are only used to print it."""
        if not rows or not rows[0]:
            raise ValueError("a grid needs at least one cell")
        width = len(rows[0])
        if any(len(row) != width for row in rows):
            raise ValueError("every row of a grid must have the same number of cells")
        if not cell_cm > 0:
            raise ValueError(f"cell_cm must be positive, got {cell_cm}")
        self._rows: tuple[tuple[Cell, ...], ...] = tuple(tuple(row) for row in rows)
        self._cell_cm = float(cell_cm)
        self._legend = legend
        self._text = text
        self._wall_rects: tuple[Rect, ...] | None = None

    @classmethod
    def from_text(
        cls,
        text: str,
        legend: Legend | Mapping[str, LegendEntry | Cell | str] | None = None,
        cell_cm: float = 10.0,
    ) -> Grid:
        """A grid from rows of characters, top row first (indentation and blank edge lines ignored)."""
        known = as_legend(legend)
        rows = text_rows(text)
        cells = read_text_grid(rows, known, "<text>")
        return cls(cells.rows, cell_cm, known, text="\n".join(row.text for row in rows))

    # -- size ------------------------------------------------------------------
    @property
    def width(self) -> int:
        """Columns."""
        return len(self._rows[0])

    @property
    def height(self) -> int:
        """Rows."""
        return len(self._rows)

    @property
    def cell_cm(self) -> float:
        """Side of one cell in cm."""
        return self._cell_cm

    @property
    def size_cm(self) -> tuple[float, float]:
        """(width, height) of the whole grid in cm."""
        return (self.width * self._cell_cm, self.height * self._cell_cm)

    @property
    def legend(self) -> Legend | None:
        """The legend the grid was read with, if any (used to print it)."""
        return self._legend

    # -- cells -------------------------------------------------------------------
    def contains(self, col: int, row: int) -> bool:
        """Whether (col, row) is a cell of this grid."""
        return 0 <= col < self.width and 0 <= row < self.height

    def cell(self, col: int, row: int) -> Cell:
        """The cell at (col, row); IndexError outside the grid (no wrap-around)."""
        if not (0 <= col < len(self._rows[0]) and 0 <= row < len(self._rows)):
            raise IndexError(f"cell ({col}, {row}) is outside the {self.width}x{self.height} grid")
        return self._rows[row][col]

    def is_wall(self, col: int, row: int) -> bool:
        """Whether the cell at (col, row) is a wall."""
        return self.cell(col, row).wall

    def cell_index_at(self, x_cm: float, y_cm: float) -> tuple[int, int] | None:
        """(col, row) of the cell containing the point, or None outside the grid."""
        if x_cm < 0 or y_cm < 0:
            return None
        col = math.floor(x_cm / self._cell_cm)
        row = math.floor(y_cm / self._cell_cm)
        if col >= len(self._rows[0]) or row >= len(self._rows):
            return None
        return (col, row)

    def cell_at(self, x_cm: float, y_cm: float) -> Cell | None:
        """The cell containing the point (cm), or None outside the grid."""
        if x_cm < 0 or y_cm < 0:
            return None
        col = int(x_cm // self._cell_cm)
        row = int(y_cm // self._cell_cm)
        rows = self._rows
        if row >= len(rows) or col >= len(rows[0]):
            return None
        return rows[row][col]

    def cell_center(self, col: int, row: int) -> tuple[float, float]:
        """The middle of a cell in cm."""
        return ((col + 0.5) * self._cell_cm, (row + 0.5) * self._cell_cm)

    def cell_rect(self, col: int, row: int) -> Rect:
        """(x0, y0, x1, y1) of a cell in cm."""
        s = self._cell_cm
        return (col * s, row * s, (col + 1) * s, (row + 1) * s)

    def cells(self) -> Iterator[tuple[int, int, Cell]]:
        """Every (col, row, cell), bottom row first."""
        for row, cells in enumerate(self._rows):
            for col, cell in enumerate(cells):
                yield col, row, cell

    def wall_cells(self) -> list[tuple[int, int]]:
        """(col, row) of every wall cell."""
        return [(col, row) for col, row, cell in self.cells() if cell.wall]

    def with_cell(self, col: int, row: int, cell: Cell) -> Grid:
        """A copy with one cell replaced."""
        self.cell(col, row)
        rows = [list(r) for r in self._rows]
        rows[row][col] = cell
        return Grid(rows, self._cell_cm, self._legend)

    # -- what other layers read ----------------------------------------------------
    def wall_rectangles(self) -> list[Rect]:
        """Walls as few non-overlapping rectangles (x0, y0, x1, y1) in cm covering exactly the wall cells."""
        if self._wall_rects is None:
            self._wall_rects = tuple(spans_to_rects(merge_cells(self.wall_cells()), self._cell_cm))
        return list(self._wall_rects)

    def wall_rows(self) -> list[list[bool]]:
        """Whether each cell is a wall, indexed [row][col]."""
        return [[cell.wall for cell in row] for row in self._rows]

    def reflected_rows(self) -> list[list[float]]:
        """COL-REFLECT reading on each cell, indexed [row][col]."""
        return [[cell.reflected for cell in row] for row in self._rows]

    def color_id_rows(self) -> list[list[int]]:
        """COL-COLOR id on each cell, indexed [row][col]."""
        return [[cell.color_id for cell in row] for row in self._rows]

    def raw_rgb_rows(self) -> list[list[tuple[float, float, float]]]:
        """RGB-RAW reading on each cell, indexed [row][col]."""
        return [[cell.raw_rgb for cell in row] for row in self._rows]

    def display_rgb_rows(self) -> list[list[tuple[int, int, int]]]:
        """The colour to draw each cell, indexed [row][col]."""
        return [[cell.display_rgb for cell in row] for row in self._rows]

    # -- text ----------------------------------------------------------------------
    def to_text(self, legend: Legend | Mapping[str, LegendEntry | Cell | str] | None = None) -> str:
        """The grid as rows of characters, top row first (one line per row, no trailing newline).

        Without a legend, a grid read from text prints exactly as it was written.
        """
        if legend is None and self._text is not None:
            return self._text
        known = as_legend(legend) if legend is not None else (self._legend or as_legend(None))
        return "\n".join("".join(known.char_for(cell) for cell in row) for row in reversed(self._rows))

    def __str__(self) -> str:
        return self.to_text()

    def __repr__(self) -> str:
        return f"Grid({self.width}x{self.height} cells of {self._cell_cm:g} cm)"

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Grid):
            return NotImplemented
        return self._cell_cm == other._cell_cm and self._rows == other._rows

    def __hash__(self) -> int:
        return hash((self._cell_cm, self._rows))
