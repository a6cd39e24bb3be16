"""A world as the editor page sees it (plain JSON), and the edited world the page sends back.

Cells are listed bottom row first (`cells[row][col]`, as in the world file's
coordinates), each as `{wall, shade, color, char, region}`: `char` is the
character the cell was written with (null once the page changes the cell) and
`region` the region its legend character puts it in.  Only the regions written
under `regions:` are editable; regions of legend characters follow their cells.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from .cell import WALL_SHADE, Cell
from .colors import EV3_COLORS
from .file_limits import (
    ANGLE_DEG,
    CELL_CM,
    MAX_CELLS_PER_SIDE,
    MAX_NAME_CHARS,
    MAX_RECTS_PER_REGION,
    MAX_REGIONS,
    MAX_STARTS,
    MIN_CELLS_PER_SIDE,
    within,
)
from .grid import Grid
from .maze_reader import read_maze
from .pose import Pose
from .rectangles import Rect, merge_cells, spans_to_rects
from .region import Region
from .robot_spec import RobotSpec
from .yaml_source import Fields, load_yaml_text

MAX_CELL_CM = CELL_CM[1]
REGION_NAME = re.compile(rf"^[^\x00-\x1f\x7f]{{1,{MAX_NAME_CHARS}}}$")
SHADE_STEPS = [round(d * 100 / 9) for d in range(10)]
"""The greys lighten and darken step through: those of the default legend's digits 0..9."""


@dataclass(frozen=True)
class EditedCell:
    """One cell as the page sends it: what it is, and the character it was written with (if unchanged)."""

    cell: Cell
    char: str | None


@dataclass
class EditedWorld:
    """What the page can change: cell size, cells (bottom row first), start poses and written regions."""

    cell_cm: float
    cells: list[list[EditedCell]]
    starts: list[Pose]
    regions: list[tuple[str, list[Rect]]]

    @property
    def width(self) -> int:
        return len(self.cells[0])

    @property
    def height(self) -> int:
        return len(self.cells)


class MazeSource:
    """A world file's text, the world read from it (its grid, starts, regions, title and robot), and
    what the editor needs to write it back."""

    def __init__(self, text: str, path: str) -> None:
        self.text = text
        self.path = path
        fields = read_maze(text, path)  # raises WorldFileError where the text is not a valid world
        self.grid: Grid = fields["grid"]
        self.starts: list[Pose] = fields["starts"]
        self.regions: dict[str, Region] = fields["regions"]
        self.title: str = fields["title"]
        self.robot: RobotSpec = fields["robot"]
        grid = self.grid
        lines = grid.to_text().split("\n")
        self.chars: list[list[str]] = [list(lines[grid.height - 1 - row]) for row in range(grid.height)]
        self.written_regions: list[tuple[str, list[Rect]]] = _written_regions(text, path, grid.cell_cm)

    def as_edited(self) -> EditedWorld:
        """The world unchanged, as the page would send it back."""
        grid = self.grid
        cells = [
            [EditedCell(grid.cell(col, row), self.chars[row][col]) for col in range(grid.width)]
            for row in range(grid.height)
        ]
        return EditedWorld(grid.cell_cm, cells, list(self.starts), list(self.written_regions))

    def to_json(self) -> dict:
        """The world for the page."""
        grid = self.grid
        legend = grid.legend
        cells = []
        for row in range(grid.height):
            cells.append(
                [
                    {
                        "wall": cell.wall,
                        "shade": cell.shade,
                        "color": cell.color,
                        "char": self.chars[row][col],
                        "region": legend.region(self.chars[row][col]) if legend is not None else None,
                    }
                    for col, cell in ((col, grid.cell(col, row)) for col in range(grid.width))
                ]
            )
        body = self.robot.body
        return {
            "file": self.path,
            "title": self.title,
            "width": grid.width,
            "height": grid.height,
            "cell_cm": grid.cell_cm,
            "cells": cells,
            "starts": [pose.as_dict() for pose in self.starts],
            "regions": [
                {"name": name, "rects": [list(r) for r in rects]} for name, rects in self.written_regions
            ],
            "robot": {
                "front_cm": body.front_cm,
                "back_cm": body.back_cm,
                "width_cm": body.width_cm,
                "color": list(self.robot.color),
            },
            "palette": {
                "colors": {name: list(color.display_rgb) for name, color in EV3_COLORS.items()},
                "wall_shade": WALL_SHADE,
                "shade_steps": SHADE_STEPS,
            },
        }


def _written_regions(text: str, path: str, cell_cm: float) -> list[tuple[str, list[Rect]]]:
    """The regions under `regions:` as rectangles in cm (cells become rectangles), in file order."""
    fields = Fields(load_yaml_text(text, path), "the maze file", None)
    node = fields.get("regions")
    if node is None or node.is_null:
        return []
    result = []
    for key, value in Fields(node, "'regions'", None).items():
        spec = value.value() or {}
        rects: list[Rect] = []
        if spec.get("cells"):
            spans = merge_cells((int(c), int(r)) for c, r in spec["cells"])
            rects += spans_to_rects(spans, cell_cm)
        if spec.get("rect_cm"):
            rects.append(tuple(float(v) for v in spec["rect_cm"]))
        for rect in spec.get("rects_cm") or []:
            rects.append(tuple(float(v) for v in rect))
        result.append((key.text, rects))
    return result


# -- reading what the page sends -------------------------------------------------------------


class BadEdit(ValueError):
    """The page sent something that is not an edited world; the message says what."""


def edited_from_json(data: object) -> EditedWorld:
    """Check and read the page's edited world; BadEdit names the first thing wrong."""
    if not isinstance(data, dict):
        raise BadEdit("the request must be a JSON object")
    allowed = {"cell_cm", "cells", "starts", "regions"}
    unknown = sorted(set(data) - allowed)
    if unknown:
        raise BadEdit(
            f"unknown field(s) {', '.join(unknown)}; the editor sends only {', '.join(sorted(allowed))}"
        )
    missing = sorted(allowed - set(data))
    if missing:
        raise BadEdit(f"missing field(s) {', '.join(missing)}")
    cell_cm = _number(data["cell_cm"], "cell_cm")
    if not within(cell_cm, CELL_CM):
        raise BadEdit(f"cell_cm must be {CELL_CM[0]:g} to {CELL_CM[1]:g} cm (docs/world-files.md, Limits)")
    rows = data["cells"]
    if not isinstance(rows, list) or not rows or not all(isinstance(row, list) for row in rows):
        raise BadEdit("cells must be a list of rows, each a list of cells")
    height, width = len(rows), len(rows[0])
    sides = (MIN_CELLS_PER_SIDE, MAX_CELLS_PER_SIDE)
    if not (within(width, sides) and within(height, sides)):
        raise BadEdit(f"the grid must be {sides[0]} to {sides[1]} cells each way, got {width}x{height}")
    if any(len(row) != width for row in rows):
        raise BadEdit("every row of cells must have the same length")
    cells = [[_cell(item, col, row) for col, item in enumerate(items)] for row, items in enumerate(rows)]
    starts_data = data["starts"]
    if not isinstance(starts_data, list) or not 1 <= len(starts_data) <= MAX_STARTS:
        raise BadEdit(f"starts must be a list of 1 to {MAX_STARTS} poses")
    size_cm = (width * cell_cm, height * cell_cm)
    starts = [_pose(item, size_cm) for item in starts_data]
    regions_data = data["regions"]
    if not isinstance(regions_data, list) or len(regions_data) > MAX_REGIONS:
        raise BadEdit(f"regions must be a list of at most {MAX_REGIONS} regions")
    regions = [_region(item) for item in regions_data]
    names = [name for name, _ in regions]
    if len(set(names)) != len(names):
        raise BadEdit("two regions have the same name; give each region its own name")
    return EditedWorld(cell_cm, cells, starts, regions)


def _number(value: object, name: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise BadEdit(f"{name} must be a number")
    return float(value)


def _cell(item: object, col: int, row: int) -> EditedCell:
    where = f"cell [{col}, {row}]"
    if not isinstance(item, dict) or not {"wall", "shade", "color"} <= set(item):
        raise BadEdit(f"{where} must be an object with wall, shade and color")
    wall, shade, color, char = item["wall"], item["shade"], item["color"], item.get("char")
    if not isinstance(wall, bool):
        raise BadEdit(f"{where}: wall must be true or false")
    if shade is not None:
        shade = _number(shade, f"{where} shade")
    if color is not None and color not in EV3_COLORS:
        raise BadEdit(f"{where}: color must be one of {', '.join(EV3_COLORS)} or null")
    if char is not None and not (isinstance(char, str) and len(char) == 1):
        raise BadEdit(f"{where}: char must be one character or null")
    try:
        cell = Cell(wall=wall, shade=shade, color=color)
    except ValueError as err:
        raise BadEdit(f"{where}: {err}") from None
    return EditedCell(cell, char)


def _pose(item: object, size_cm: tuple[float, float]) -> Pose:
    """A start inside the grid; a heading past one turn either way is turned back into it."""
    if not isinstance(item, dict) or set(item) != {"x_cm", "y_cm", "heading_deg"}:
        raise BadEdit("a start must be an object with x_cm, y_cm and heading_deg")
    x, y = _number(item["x_cm"], "x_cm"), _number(item["y_cm"], "y_cm")
    if not (0 <= x <= size_cm[0] and 0 <= y <= size_cm[1]):
        raise BadEdit(
            f"a start must lie on the grid (0..{size_cm[0]:g} x 0..{size_cm[1]:g} cm), got {x:g}, {y:g}"
        )
    heading = _number(item["heading_deg"], "heading_deg")
    if not within(heading, ANGLE_DEG):
        heading = math.remainder(heading, 360.0)
    return Pose(x, y, heading)


def _region(item: object) -> tuple[str, list[Rect]]:
    if not isinstance(item, dict) or set(item) != {"name", "rects"}:
        raise BadEdit("a region must be an object with name and rects")
    name, rects = item["name"], item["rects"]
    if not isinstance(name, str) or not REGION_NAME.match(name) or name != name.strip():
        raise BadEdit(
            f"region name {name!r} must be 1 to {MAX_NAME_CHARS} characters, not starting or ending with a space"
        )
    if not isinstance(rects, list) or not 1 <= len(rects) <= MAX_RECTS_PER_REGION:
        raise BadEdit(f"region {name!r} needs 1 to {MAX_RECTS_PER_REGION} rectangles")
    result: list[Rect] = []
    for rect in rects:
        if not isinstance(rect, list) or len(rect) != 4:
            raise BadEdit(f"region {name!r}: a rectangle is [x0, y0, x1, y1] in cm")
        x0, y0, x1, y1 = (_number(v, f"region {name!r} rectangle") for v in rect)
        result.append((x0, y0, x1, y1))
    return name, result
