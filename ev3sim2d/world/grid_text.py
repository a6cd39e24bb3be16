"""Reading the rows of a text grid (top row first) into cells, naming the line and column of any mistake."""

from __future__ import annotations

from dataclasses import dataclass

from .cell import Cell
from .legend import Legend
from .source_error import WorldFileError

_YAML_PLAIN_KEY_CHARS = set("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.$+=()^;")


@dataclass(frozen=True)
class TextRow:
    """One row of a text grid and where it is written (1-based; None when unknown)."""

    text: str
    line: int | None = None
    column: int | None = None

    def column_of(self, index: int) -> int | None:
        """The file column of the character at `index` in this row."""
        return None if self.column is None else self.column + index


@dataclass(frozen=True)
class TextGridCells:
    """What a text grid says: cells indexed [row][col] with row 0 at the bottom, and legend regions."""

    rows: list[list[Cell]]
    region_cells: dict[str, list[tuple[int, int]]]


def read_text_grid(rows: list[TextRow], legend: Legend, path: str) -> TextGridCells:
    """Cells for each character; refuses spaces, unknown characters and ragged rows."""
    if not rows:
        raise WorldFileError(
            path, None, None, "the grid has no rows; write one line of cells per row, e.g. `#####`"
        )
    width = len(rows[0].text)
    cells_top_first: list[list[Cell]] = []
    region_cells: dict[str, list[tuple[int, int]]] = {}
    height = len(rows)
    for i, row in enumerate(rows):
        text = row.text
        for j, char in enumerate(text):
            if char.isspace():
                raise _at(path, row, j, f"a {_name(char)} is not a cell; write '.' for floor or '#' for wall")
            if char not in legend:
                raise _at(path, row, j, _unknown_char_message(char, legend))
        if len(text) != width:
            raise _at(
                path,
                row,
                min(len(text), width),
                f"row {i + 1} of the grid (from the top) has {len(text)} cells but the first row has {width}; "
                "every row needs the same number of cells",
            )
        row_index = height - 1 - i
        cells_top_first.append([legend.cell(char) for char in text])
        for col, char in enumerate(text):
            region = legend.region(char)
            if region is not None:
                region_cells.setdefault(region, []).append((col, row_index))
    return TextGridCells(rows=cells_top_first[::-1], region_cells=region_cells)


def text_rows(text: str, first_line: int = 1, column: int = 1) -> list[TextRow]:
    """Rows of an inline text block: blank lines around it dropped, common indentation and trailing spaces removed."""
    lines = text.split("\n")
    while lines and not lines[0].strip():
        lines.pop(0)
        first_line += 1
    while lines and not lines[-1].strip():
        lines.pop()
    indents = [len(line) - len(line.lstrip(" ")) for line in lines if line.strip()]
    indent = min(indents, default=0)
    return [TextRow(line[indent:].rstrip(), first_line + i, column + indent) for i, line in enumerate(lines)]


def first_non_wall_border_cell(rows: list[TextRow], cells: list[list[Cell]]) -> tuple[TextRow, int] | None:
    """The first border cell (reading order) that is not a wall, as (row, index in row); None if all are walls."""
    height = len(cells)
    for i, row in enumerate(rows):
        row_cells = cells[height - 1 - i]
        on_edge = i in (0, height - 1)
        for j, cell in enumerate(row_cells):
            if (on_edge or j in (0, len(row_cells) - 1)) and not cell.wall:
                return row, j
    return None


def _unknown_char_message(char: str, legend: Legend) -> str:
    key = char if char in _YAML_PLAIN_KEY_CHARS else f'"{char}"'
    return (
        f"unknown cell character {char!r}; known characters: {' '.join(legend.chars)}; "
        f"to add it, write under `legend:` e.g. `{key}: red` or `{key}: {{shade: 40}}`"
    )


def _name(char: str) -> str:
    return "tab" if char == "\t" else "space"


def _at(path: str, row: TextRow, index: int, message: str) -> WorldFileError:
    return WorldFileError(path, row.line, row.column_of(index), message)
