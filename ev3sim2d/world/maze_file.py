"""Maze files (YAML) in, World out; and finding the mazes that ship with ev3sim2d.

The format is described, with a full example, in docs/world-files.md; maze_reader.py reads it and
says where a file is wrong.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from .cell import Cell
from .grid import Grid
from .grid_text import read_text_grid, text_rows
from .legend import Legend, LegendEntry, as_legend
from .maze_reader import DEFAULT_CELL_CM, middle_floor_cell, read_maze
from .pose import Pose
from .rectangles import merge_cells, spans_to_rects
from .region import Region
from .robot_spec import RobotSpec, default_robot
from .source_error import WorldFileError
from .world import World
from .yaml_source import Fields, load_yaml_text, read_text_file

# -- reading ----------------------------------------------------------------------------


def load_maze(path: str | Path) -> World:
    """Read a maze file."""
    return parse_maze(read_text_file(path), str(path))


def parse_maze(text: str, path: str = "<string>", robots: bool = True) -> World:
    """Read a maze from YAML text; `path` names it in errors and resolves a relative `robot:` file
    (robots=False: robot files are not looked for, see read_maze)."""
    return World(**read_maze(text, path, robots))


def maze_from_text_grid(
    grid_text: str,
    start: Pose | tuple[int, int] | None = None,
    *,
    cell_cm: float = DEFAULT_CELL_CM,
    legend: Legend | Mapping[str, LegendEntry | Cell | str] | None = None,
    name: str = "inline",
    robot: RobotSpec | None = None,
) -> World:
    """A World for tests: a text grid, a start (a Pose, a (col, row) cell, or the middle floor cell), the default robot.

    Legend regions become regions; border walls are not required here.
    """
    known = as_legend(legend)
    rows = text_rows(grid_text)
    cells = read_text_grid(rows, known, "<text>")
    grid = Grid(cells.rows, cell_cm, known, text="\n".join(row.text for row in rows))
    if isinstance(start, Pose):
        pose = start
    else:
        col, row = start if start is not None else middle_floor_cell(grid)
        pose = Pose(*grid.cell_center(col, row), 0.0)
    regions = {
        region: Region(region, tuple(spans_to_rects(merge_cells(spots), cell_cm)))
        for region, spots in cells.region_cells.items()
    }
    return World(name, name, "", grid, [pose], regions, robot or default_robot())


# -- shipped mazes ----------------------------------------------------------------------------


def shipped_mazes_dir() -> Path:
    """The folder of mazes that come with ev3sim2d (an installed copy first, else the repository's `mazes/`)."""
    package = Path(__file__).resolve().parents[1]
    for candidate in (package / "_mazes", package / "mazes"):
        if candidate.is_dir():
            return candidate
    return package.parent / "mazes"


def list_shipped_mazes() -> list[tuple[str, str]]:
    """(name, title) of every shipped maze, sorted by name."""
    result = []
    for path in sorted(shipped_mazes_dir().glob("*.yaml")):
        root = load_yaml_text(read_text_file(path), str(path))
        title_node = Fields(root, "the maze file", None).get("title")
        result.append((path.stem, title_node.text if title_node is not None else path.stem))
    return result


def find_maze(name_or_path: str | Path) -> Path:
    """An existing file path, else a shipped maze by name ('line', 'line.yaml', 'mazes/line.yaml')."""
    candidate = Path(name_or_path)
    if candidate.is_file():
        return candidate
    stem = candidate.stem if candidate.suffix in (".yaml", ".yml") else candidate.name
    shipped = shipped_mazes_dir() / f"{stem}.yaml"
    if shipped.is_file():
        return shipped
    names = ", ".join(name for name, _ in list_shipped_mazes())
    raise WorldFileError(
        str(name_or_path),
        None,
        None,
        f"no maze file or shipped maze by this name; shipped mazes: {names}; or give the path of a .yaml file",
    )
