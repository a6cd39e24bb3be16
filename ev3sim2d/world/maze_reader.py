"""A world file's YAML read into the fields of a World, each checked.

The format is described, with a full example, in docs/world-files.md.  Every
mistake a user can make in a world file raises WorldFileError naming the file,
the line (and column) and what to write instead.  This module knows nothing of
the World class: world.py builds a World from what it reads, and so can reread
its own text after an edit.
"""

from __future__ import annotations

import difflib
from pathlib import Path
from typing import Any

from .button_press import parse_press
from .colors import DEFAULT_SURFACES, EV3_COLORS, REFLECT_RANGE, RGB_RAW_RANGE, Surfaces
from .file_limits import (
    ANGLE_DEG,
    CELL_CM,
    MAX_BUTTON_PRESSES,
    MAX_CELLS_PER_SIDE,
    MAX_DESCRIPTION_CHARS,
    MAX_NAME_CHARS,
    MAX_PATH_CHARS,
    MAX_RECTS_PER_REGION,
    MAX_REGION_CELLS,
    MAX_REGIONS,
    MAX_STARTS,
    MAX_TITLE_CHARS,
    MIN_CELLS_PER_SIDE,
    within,
)
from .grid import Grid
from .grid_text import TextRow, first_non_wall_border_cell, read_text_grid
from .legend import DEFAULT_LEGEND, legend_from_node
from .pose import Pose
from .rectangles import Rect, merge_cells, spans_to_rects
from .region import Region
from .robot_spec import (
    RobotSpec,
    default_robot,
    find_robot,
    load_robot,
    robot_from_mapping,
    shipped_robot_names,
)
from .source_error import WorldFileError
from .yaml_source import Fields, Node, foreign_path_hint, load_yaml_text, written_path

DEFAULT_AMBIENT = 10.0
"""Ambient light (0..100) when a world file gives none: a lit classroom as the EV3 sees it."""
MAZE_KEYS = (
    "title",
    "description",
    "cell_cm",
    "legend",
    "grid",
    "start",
    "regions",
    "robot",
    "ambient",
    "buttons",
    "surfaces",
)
DEFAULT_CELL_CM = 10.0
MIN_CELLS = MIN_CELLS_PER_SIDE

_GRID_HELP = (
    "write `grid: |` and below it one line of cells per row, top row first (or a list of quoted strings)"
)
_START_EXAMPLE = "start: {cell: [1, 1], heading_deg: 0}"
_START_KEYS = ("cell", "x_cm", "y_cm", "heading_deg", "robot")


# -- reading ----------------------------------------------------------------------------


def read_maze(text: str, path: str = "<string>", robots: bool = True) -> dict[str, Any]:
    """A World's fields (its keyword arguments) read from a world file's YAML text; `path` names the
    file in errors and resolves a relative `robot:` file.  robots=False: its robot files are not looked
    for (the world and start robots are the driving base): a trace's world, drawn from a trace that
    holds its robots itself, far from the folder its world file was in."""
    root = load_yaml_text(text, path)
    if not root.is_mapping:
        raise root.error(f"a maze file is a mapping of keys like `title: My maze`, got {root.describe()}")
    fields = Fields(root, "the maze file", MAZE_KEYS)
    name = _name_from_path(path)
    title = fields.text("title", default=name, example="title: My maze")
    _check_length(fields, "title", title, MAX_TITLE_CHARS)
    description = fields.text("description", default=None, example="description: Drive to the green square.")
    if description is None:
        description = header_comment(text)[:MAX_DESCRIPTION_CHARS]
    _check_length(fields, "description", description, MAX_DESCRIPTION_CHARS)
    cell_cm = fields.number("cell_cm", default=DEFAULT_CELL_CM, unit="cm", example="cell_cm: 10")
    if not within(cell_cm, CELL_CM):
        raise fields.get("cell_cm").error(
            f"'cell_cm', the size of a grid cell, must be {CELL_CM[0]:g} to {CELL_CM[1]:g} cm, got {cell_cm:g} "
            "(the shipped worlds use 2 to 20 cm; a finer cell is smaller than the colour sensor's spot); "
            "write e.g. `cell_cm: 10`"
        )
    legend = legend_from_node(fields.get("legend")) if "legend" in fields else DEFAULT_LEGEND
    grid_node = fields.require("grid", "grid: |")
    rows = _grid_rows(grid_node, text)
    cells = read_text_grid(rows, legend, path)
    grid = Grid(cells.rows, cell_cm, legend, text="\n".join(row.text for row in rows))
    _check_size_and_border(grid_node, rows, grid)
    starts, start_robots = _starts(fields.require("start", _START_EXAMPLE), grid, path if robots else None)
    regions = _regions(fields.get("regions"), cells.region_cells, grid)
    robot = _robot(fields.get("robot"), path) if robots else default_robot()
    ambient = fields.number("ambient", default=DEFAULT_AMBIENT, unit="0..100", example="ambient: 10")
    if not 0 <= ambient <= 100:
        raise fields.get("ambient").error(f"'ambient' is a light level from 0 to 100, got {ambient:g}")
    surfaces = _surfaces(fields.get("surfaces"))
    buttons = []
    press_nodes = (
        fields.get("buttons").as_list("buttons", "buttons: [enter@2.0]") if "buttons" in fields else []
    )
    if len(press_nodes) > MAX_BUTTON_PRESSES:
        raise fields.get("buttons").error(
            f"'buttons' lists {len(press_nodes):,} presses, more than the {MAX_BUTTON_PRESSES:,} a world may "
            "script (docs/world-files.md, Limits); script fewer"
        )
    for node in press_nodes:
        try:
            buttons.append(parse_press(node.as_text("buttons", "buttons: [enter@2.0]")))
        except ValueError as err:
            raise node.error(str(err)) from None
    return dict(
        name=name,
        title=title,
        description=description,
        grid=grid,
        starts=starts,
        regions=regions,
        robot=robot,
        source=None if path.startswith("<") else path,
        text=text,
        ambient=ambient,
        buttons=buttons,
        start_robots=start_robots,
        surfaces=surfaces,
    )


def middle_floor_cell(grid: Grid) -> tuple[int, int]:
    """The floor cell nearest the middle of the grid."""
    mid_col, mid_row = (grid.width - 1) / 2, (grid.height - 1) / 2
    floor = [(col, row) for col, row, cell in grid.cells() if not cell.wall]
    if not floor:
        raise ValueError("the grid has no floor cell to start on")
    return min(floor, key=lambda cr: ((cr[0] - mid_col) ** 2 + (cr[1] - mid_row) ** 2, cr))


def header_comment(text: str) -> str:
    """The comment lines at the top of a file, without their '#', as the world's description."""
    lines: list[str] = []
    for line in text.splitlines():
        stripped = line.strip()
        if not stripped.startswith("#"):
            break
        lines.append(stripped.lstrip("#").strip())
    return " ".join(lines).strip()


def _name_from_path(path: str) -> str:
    return "untitled" if path.startswith("<") else Path(path).stem


def _grid_rows(node: Node, text: str) -> list[TextRow]:
    """The grid's rows with their file positions, from a `|` block or a list of strings."""
    if node.is_sequence:
        _check_rows(node, len(node.raw.value))
        rows = []
        for item in node.as_list("grid"):
            row = item.as_text("grid", '- "#####"')
            quoted = item.style in ("'", '"')
            _check_row_width(item, len(row.rstrip()))
            rows.append(TextRow(row.rstrip(), item.line, item.column + (1 if quoted else 0)))
        return rows
    if node.is_scalar and node.style == "|":
        source_lines = text.split("\n")
        _check_rows(node, node.raw.value.strip("\n").count("\n") + 1)
        value_lines = node.raw.value.split("\n")
        first_line = node.line + 1  # a literal block starts on the line after `|`
        indent = _block_indent(source_lines, node.line, value_lines)
        rows = [TextRow(value.rstrip(), first_line + i, indent + 1) for i, value in enumerate(value_lines)]
        while rows and not rows[0].text:
            rows.pop(0)
        while rows and not rows[-1].text:
            rows.pop()
        for row in rows:
            if not row.text:
                raise WorldFileError(node.path, row.line, None, "an empty line inside the grid; remove it")
            if len(row.text) > MAX_CELLS_PER_SIDE:
                raise WorldFileError(node.path, row.line, row.column, _too_wide(len(row.text)))
        return rows
    if node.is_null:
        raise node.error(f"'grid' is empty (a '#' right after `grid:` starts a YAML comment); {_GRID_HELP}")
    raise node.error(f"'grid' must be rows of cell characters; {_GRID_HELP}")


def _check_rows(node: Node, count: int) -> None:
    """A grid of at most MAX_CELLS_PER_SIDE rows, checked before a row is read."""
    if count > MAX_CELLS_PER_SIDE:
        raise node.error(
            f"the grid has {count:,} rows; a world is at most {MAX_CELLS_PER_SIDE} cells each way "
            "(docs/world-files.md, Limits); make the grid smaller or the cells bigger (`cell_cm`)",
            column=False,
        )


def _check_row_width(node: Node, width: int) -> None:
    if width > MAX_CELLS_PER_SIDE:
        raise node.error(_too_wide(width))


def _too_wide(width: int) -> str:
    return (
        f"this row of the grid has {width:,} cells; a world is at most {MAX_CELLS_PER_SIDE} cells each way "
        "(docs/world-files.md, Limits); make the grid smaller or the cells bigger (`cell_cm`)"
    )


def _check_length(fields: Fields, name: str, text: str, limit: int) -> None:
    """Text under `name` of at most `limit` characters."""
    if len(text) > limit and name in fields:
        raise fields.get(name).error(
            f"'{name}' is {len(text):,} characters long, more than the {limit:,} it may be; shorten it"
        )


def _block_indent(source_lines: list[str], block_line: int, value_lines: list[str]) -> int:
    """How far the block's rows are indented in the file (0-based count of spaces)."""
    for i, value in enumerate(value_lines):
        if value.strip():
            index = block_line + i  # 0-based index of the file line holding value line i
            if index < len(source_lines):
                source = source_lines[index].rstrip("\r")
                if source.endswith(value):
                    return len(source) - len(value)
            break
    return 0


def _check_size_and_border(node: Node, rows: list[TextRow], grid: Grid) -> None:
    if grid.width < MIN_CELLS or grid.height < MIN_CELLS:
        raise node.error(
            f"the grid is {grid.width}x{grid.height} cells; a world needs at least {MIN_CELLS}x{MIN_CELLS} "
            "(a wall all round and floor inside)",
            column=False,
        )
    cells = [[grid.cell(col, row) for col in range(grid.width)] for row in range(grid.height)]
    found = first_non_wall_border_cell(rows, cells)
    if found is not None:
        row, index = found
        raise WorldFileError(
            node.path,
            row.line,
            row.column_of(index),
            f"border cell '{row.text[index]}' is not a wall; border cells must be walls so the robot cannot "
            "leave the world; write '#' or another wall character",
        )


# -- starts --------------------------------------------------------------------------------


def _starts(node: Node, grid: Grid, path: str | None) -> tuple[list[Pose], list[RobotSpec | None]]:
    """The start poses, and per start the robot it names (None: the world's robot; path None: robot files
    are not looked for)."""
    items = node.as_list("start", _START_EXAMPLE) if node.is_sequence else [node]
    if not items:
        raise node.error(f"'start' needs at least one pose; write e.g. `{_START_EXAMPLE}`")
    if len(items) > MAX_STARTS:
        raise node.error(
            f"'start' lists {len(items):,} starts; a world has at most {MAX_STARTS} robots "
            "(docs/world-files.md, Limits); remove some"
        )
    poses = [_start(item, grid) for item in items]
    robots = [_start_robot(item, path) if path is not None else None for item in items]
    return poses, robots


def _start_robot(node: Node, path: str) -> RobotSpec | None:
    """The robot a start names with `robot: FILE` (found as the world's `robot:` is), or None."""
    fields = node.as_fields("start", _START_KEYS, _START_EXAMPLE)
    return _robot(fields.get("robot"), path) if "robot" in fields else None


def _start(node: Node, grid: Grid) -> Pose:
    if not node.is_mapping:
        raise node.error(f"a start is a mapping like `{_START_EXAMPLE}`, got {node.describe()}")
    fields = node.as_fields("start", _START_KEYS, _START_EXAMPLE)
    heading = fields.number(
        "heading_deg", default=0.0, unit="degrees, 0 = +x, counter-clockwise", example="heading_deg: 90"
    )
    if not within(heading, ANGLE_DEG):
        raise fields.get("heading_deg").error(
            f"'heading_deg' must be {ANGLE_DEG[0]:g} to {ANGLE_DEG[1]:g} degrees (one turn either way; "
            f"0 = +x, 90 = +y), got {heading:g}; write e.g. `heading_deg: 90`"
        )
    by_cell = "cell" in fields
    by_cm = "x_cm" in fields or "y_cm" in fields
    if by_cell and by_cm:
        raise node.error(
            "give the start either as `cell: [col, row]` or as `x_cm` and `y_cm`, not both", column=False
        )
    if not by_cell and not by_cm:
        raise node.error(
            "a start needs a position: `cell: [col, row]` (from the bottom-left, both from 0) or `x_cm` and `y_cm`",
            column=False,
        )
    if by_cell:
        cell_node = fields.get("cell")
        col, row = _cell_pair(cell_node, "cell", "cell: [1, 1]")
        if not grid.contains(col, row):
            raise cell_node.error(f"start cell [{col}, {row}] is outside the grid; {_grid_extent(grid)}")
        if grid.is_wall(col, row):
            raise cell_node.error(f"start cell [{col}, {row}] is a wall; start the robot on a floor cell")
        x, y = grid.cell_center(col, row)
        return Pose(x, y, heading)
    x = fields.number("x_cm", unit="cm", example="x_cm: 35")
    y = fields.number("y_cm", unit="cm", example="y_cm: 55")
    index = grid.cell_index_at(x, y)
    if index is None:
        width, height = grid.size_cm
        raise node.error(
            f"start x_cm {x:g}, y_cm {y:g} is outside the grid (0..{width:g} x 0..{height:g} cm)",
            column=False,
        )
    if grid.is_wall(*index):
        raise node.error(
            f"start x_cm {x:g}, y_cm {y:g} is inside the wall cell [{index[0]}, {index[1]}]; "
            "start the robot on a floor cell",
            column=False,
        )
    return Pose(x, y, heading)


def _cell_pair(node: Node, name: str, example: str) -> tuple[int, int]:
    items = node.as_list(name, example)
    if len(items) != 2:
        raise node.error(f"'{name}' must be [col, row], two whole numbers; write e.g. `{example}`")
    return items[0].as_int(name, example), items[1].as_int(name, example)


def _grid_extent(grid: Grid) -> str:
    return f"columns are 0..{grid.width - 1} and rows 0..{grid.height - 1}, counted from the bottom-left"


# -- regions ----------------------------------------------------------------------------------


def _regions(
    node: Node | None, legend_cells: dict[str, list[tuple[int, int]]], grid: Grid
) -> dict[str, Region]:
    written = (
        node.as_fields("regions", None, "regions: {goal: {cells: [[1, 1]]}}") if node is not None else None
    )
    if written is not None and len(written) > MAX_REGIONS:
        raise node.error(
            f"'regions' names {len(written):,} regions, more than the {MAX_REGIONS} a world may have "
            "(docs/world-files.md, Limits); join some"
        )
    for name in written or []:
        if len(name) > MAX_NAME_CHARS or not name.strip() or any(ord(c) < 32 or ord(c) == 127 for c in name):
            raise written.key(name).error(
                f"a region's name is 1 to {MAX_NAME_CHARS} characters, not control characters; "
                "write e.g. `goal:`"
            )
    regions: dict[str, Region] = {}
    names = list(written or []) + [name for name in legend_cells if written is None or name not in written]
    for name in names:
        spots = list(legend_cells.get(name, []))
        rects: list[Rect] = []
        if written is not None and name in written:
            _read_region(written.get(name), name, grid, spots, rects)
        spans = merge_cells(spots)
        regions[name] = Region(name, tuple(spans_to_rects(spans, grid.cell_cm)) + tuple(rects))
    return regions


def _read_region(node: Node, name: str, grid: Grid, spots: list[tuple[int, int]], rects: list[Rect]) -> None:
    example = "{cells: [[1, 1], [2, 1]]} or {rect_cm: [10, 10, 40, 30]}"
    fields = node.as_fields(name, ("cells", "rect_cm", "rects_cm"), f"{name}: {example}")
    if len(fields) == 0:
        raise node.error(
            f"region '{name}' needs `cells` or `rect_cm`; write e.g. `{name}: {example}`", column=False
        )
    if "cells" in fields:
        cell_nodes = fields.get("cells").as_list("cells", "cells: [[1, 1], [2, 1]]")
        if len(cell_nodes) > MAX_REGION_CELLS:
            raise fields.get("cells").error(
                f"region '{name}' lists {len(cell_nodes):,} cells, more than a grid has "
                f"({MAX_CELLS_PER_SIDE}x{MAX_CELLS_PER_SIDE}); use `rect_cm` for big regions"
            )
        for item in cell_nodes:
            col, row = _cell_pair(item, "cells", "cells: [[1, 1], [2, 1]]")
            if not grid.contains(col, row):
                raise item.error(
                    f"region '{name}' cell [{col}, {row}] is outside the grid; {_grid_extent(grid)}"
                )
            spots.append((col, row))
    rect_nodes = [fields.get("rect_cm")] if "rect_cm" in fields else []
    if "rects_cm" in fields:
        rect_nodes += fields.get("rects_cm").as_list(
            "rects_cm", "rects_cm: [[0, 0, 20, 20], [40, 0, 60, 20]]"
        )
    if len(rect_nodes) > MAX_RECTS_PER_REGION:
        raise fields.get("rects_cm").error(
            f"region '{name}' has {len(rect_nodes):,} rectangles, more than the {MAX_RECTS_PER_REGION} a region "
            "may have (docs/world-files.md, Limits); join some"
        )
    for rect_node in rect_nodes:
        rects.append(_rect(rect_node, name, grid))


def _rect(node: Node, name: str, grid: Grid) -> Rect:
    x0, y0, x1, y1 = node.as_numbers("rect_cm", 4, "cm", "rect_cm: [10, 10, 40, 30]")
    if not (x0 < x1 and y0 < y1):
        raise node.error(f"region '{name}' rectangle must be [x0, y0, x1, y1] with x0 < x1 and y0 < y1 (cm)")
    width, height = grid.size_cm
    if x0 < 0 or y0 < 0 or x1 > width or y1 > height:
        raise node.error(
            f"region '{name}' rectangle reaches outside the grid (0..{width:g} x 0..{height:g} cm)"
        )
    return (x0, y0, x1, y1)


# -- surfaces --------------------------------------------------------------------------------

_SURFACES_EXAMPLE = "surfaces: {white: {reflect: 92, rgb_raw: [250, 250, 240]}, black: {reflect: 4}}"


def _surfaces(node: Node | None) -> Surfaces:
    """The world's calibration of its floor: per EV3 colour, what COL-REFLECT and RGB-RAW read on it."""
    if node is None:
        return DEFAULT_SURFACES
    fields = node.as_fields("surfaces", None, _SURFACES_EXAMPLE)
    calibrated: dict[str, dict] = {}
    reflect_nodes: dict[str, Node] = {}
    low, high = REFLECT_RANGE
    raw_low, raw_high = RGB_RAW_RANGE
    for name in fields:
        if name not in EV3_COLORS:
            close = difflib.get_close_matches(name.lower(), EV3_COLORS, n=1)
            hint = f"did you mean '{close[0]}'? " if close else ""
            raise fields.key(name).error(
                f"unknown colour '{name}' in 'surfaces'; {hint}calibrate the EV3 colours: {', '.join(EV3_COLORS)} "
                "(greys follow black and white)"
            )
        example = f"{name}: {{reflect: 50, rgb_raw: [150, 150, 150]}}"
        entry = fields.get(name).as_fields(name, ("reflect", "rgb_raw"), example)
        if len(entry) == 0:
            raise fields.get(name).error(
                f"'{name}' needs what the sensor reads on it: `reflect` (COL-REFLECT) and/or `rgb_raw` (RGB-RAW); "
                f"write e.g. `{example}`"
            )
        values: dict = {}
        if "reflect" in entry:
            reflect = entry.number("reflect", unit="COL-REFLECT, 0..100", example="reflect: 50")
            if not low <= reflect <= high:
                raise entry.get("reflect").error(
                    f"'reflect' is a COL-REFLECT reading, {low:g} to {high:g} (reflected_light_intensity), "
                    f"got {reflect:g}"
                )
            values["reflect"] = reflect
            reflect_nodes[name] = entry.get("reflect")
        if "rgb_raw" in entry:
            rgb_node = entry.get("rgb_raw")
            rgb = rgb_node.as_numbers("rgb_raw", 3, "RGB-RAW", "rgb_raw: [150, 150, 150]")
            if not all(raw_low <= v <= raw_high for v in rgb):
                raise rgb_node.error(
                    f"'rgb_raw' is an RGB-RAW reading, [red, green, blue] with {raw_low:g} to {raw_high:g} each "
                    f"(python-ev3dev2's ColorSensor.raw; white paper reads about 300), got "
                    f"[{', '.join(f'{v:g}' for v in rgb)}]"
                )
            values["rgb_raw"] = tuple(rgb)
        calibrated[name] = values
    surfaces = Surfaces(calibrated)
    black, white = surfaces.reflected("black", 0.0), surfaces.reflected("white", 0.0)
    if not black < white:
        blame = reflect_nodes.get("white") or reflect_nodes["black"]
        raise blame.error(
            f"white must reflect more than black (white reads {white:g}, black {black:g}): greys lie between "
            "them; calibrate both, e.g. `white: {reflect: 92}` and `black: {reflect: 4}`"
        )
    return surfaces


# -- robot ----------------------------------------------------------------------------------


def _robot(node: Node | None, path: str) -> RobotSpec:
    if node is None:
        return default_robot()
    if node.is_mapping:
        return robot_from_mapping(node, source=None if path.startswith("<") else path)
    if node.is_scalar and not node.is_null:
        if len(node.text) > MAX_PATH_CHARS or "\0" in node.text:
            raise node.error(
                f"'robot' names a file by a path of at most {MAX_PATH_CHARS:,} characters (no NUL characters); "
                "write e.g. `robot: robots/my-bot.yaml`"
            )
        base_dir = None if path.startswith("<") else Path(path).parent
        found = find_robot(written_path(node.text), base_dir)  # `robots\bot.yaml` from Windows too
        if found is None:
            shipped = ", ".join(shipped_robot_names())
            raise node.error(
                f"no robot file '{node.text}' (looked next to the maze file, in the current folder, "
                f"and among the shipped robots: {shipped}); check the name or write the robot inline"
                + foreign_path_hint(node.text)
            )
        return load_robot(found)
    raise node.error(
        f"'robot' must be a robot file name or a mapping describing the robot, got {node.describe()}"
    )
