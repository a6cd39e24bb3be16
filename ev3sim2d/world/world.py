"""A world as read from a maze file: the grid, where robots start, named regions and the robots to build."""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from ..results.output_files import write_file
from .button_press import ButtonPress
from .cell import Cell
from .colors import DEFAULT_SURFACES, Surfaces
from .grid import Grid
from .legend import LegendEntry, cell_from_words
from .maze_reader import DEFAULT_AMBIENT, middle_floor_cell, read_maze
from .maze_writer import new_maze_text, write_maze_text
from .pose import Pose
from .rectangles import Rect, merge_cells, spans_to_rects
from .region import Region
from .robot_spec import RobotSpec
from .world_json import EditedCell, EditedWorld, MazeSource


@dataclass
class World:
    """Everything a maze file says; `source` is its path and `text` its YAML.

    Build one in Python with `World.from_text`, change it with `set_cell` and `add_region`, and write
    it with `save`: `text` always holds the YAML of the world as it is now, so a run records (and
    draws) the world as changed, and `load_maze` reads a saved file back to an equal world.
    """

    name: str
    title: str
    description: str
    grid: Grid
    starts: list[Pose]
    regions: dict[str, Region]
    robot: RobotSpec
    source: str | None = None
    text: str | None = None
    ambient: float = DEFAULT_AMBIENT
    buttons: list[ButtonPress] = field(default_factory=list)  # scripted presses of the brick's buttons
    # per start pose: the robot that start names (`robot:` in it), or None for the world's robot
    start_robots: list[RobotSpec | None] = field(default_factory=list)
    # what the colour sensor reads on this world's floor (`surfaces:`: a calibration for its mat)
    surfaces: Surfaces = DEFAULT_SURFACES

    @property
    def start(self) -> Pose:
        """The first start pose (the one a single robot uses)."""
        return self.starts[0]

    def start_robot(self, index: int) -> RobotSpec:
        """The robot that starts at start pose `index`: the one that start names, else the world's robot."""
        own = self.start_robots[index] if index < len(self.start_robots) else None
        return own if own is not None else self.robot

    def region(self, name: str) -> Region:
        """The region called `name`; KeyError listing the known names otherwise."""
        try:
            return self.regions[name]
        except KeyError:
            known = ", ".join(self.regions) or "none"
            raise KeyError(f"world {self.name!r} has no region {name!r}; its regions: {known}") from None

    def regions_at(self, x_cm: float, y_cm: float) -> list[str]:
        """Names of the regions containing the point."""
        return [name for name, region in self.regions.items() if region.contains(x_cm, y_cm)]

    # -- building in Python ----------------------------------------------------------------------

    @classmethod
    def from_text(
        cls,
        grid_text: str,
        *,
        cell_cm: float = 10.0,
        starts: Iterable[Pose | tuple] | None = None,
        legend: Mapping[str, LegendEntry | Cell | str] | None = None,
        name: str = "world",
        title: str = "",
        description: str = "",
        robot: str | None = None,
    ) -> World:
        """A world from a text grid, top row first, in a world file's notation (docs/world-files.md).

        `#` wall, `.` white floor, `0`-`9` greys, `k b g y r w n` the EV3 colours; `legend` adds
        characters (`{"G": "green", "d": "shade 30"}`).  The border must be walls, as in a file.
        `starts` are where robots start: (col, row) or (col, row, heading_deg) cells counted from the
        bottom-left, or Poses in cm; none: the floor cell nearest the middle, facing +x.  `robot` names
        a robot file (a shipped robot's name or a path); none: the default robot.
        Raises WorldFileError naming the row and column of a mistake in the grid.
        """
        if starts is None:
            probe = Grid.from_text(grid_text, legend, cell_cm)
            starts = [middle_floor_cell(probe)]
        text = new_maze_text(
            grid_text,
            cell_cm=cell_cm,
            starts=list(starts),
            legend=legend,
            title=title or name,
            description=description,
            robot=robot,
        )
        world = cls(**read_maze(text, f"<World.from_text {name}>"))
        world.name = name
        return world

    def set_cell(self, col: int, row: int, cell: Cell | str) -> None:
        """Make cell (col, row) (from the bottom-left, both from 0) a wall or floor.

        `cell` is a character of the grid's legend (`"#"`, `"."`, `"g"`, `"5"`), words (`"wall"`,
        `"green"`, `"shade 40"`) or a Cell.  Regions are changed only by `add_region`.
        """
        if not self.grid.contains(col, row):
            raise IndexError(
                f"cell ({col}, {row}) is outside the {self.grid.width}x{self.grid.height} grid; "
                f"columns are 0..{self.grid.width - 1} and rows 0..{self.grid.height - 1}, from the bottom-left"
            )
        self.grid = self.grid.with_cell(col, row, self._cell(cell))
        self._rewrite()

    def add_region(
        self,
        name: str,
        *,
        rect_cm: Rect | None = None,
        cells: Iterable[tuple[int, int]] = (),
    ) -> Region:
        """Name a part of the floor, for lessons and checks: a rectangle (x0, y0, x1, y1) in cm and/or cells."""
        if name in self.regions:
            raise ValueError(f"world {self.name!r} already has a region {name!r}; choose another name")
        rects: list[Rect] = []
        width, height = self.grid.size_cm
        if rect_cm is not None:
            x0, y0, x1, y1 = (float(v) for v in rect_cm)
            if not (0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height):
                raise ValueError(
                    f"region {name!r}: rect_cm {tuple(rect_cm)} must be (x0, y0, x1, y1) with x0 < x1, y0 < y1, "
                    f"inside the grid's 0..{width:g} x 0..{height:g} cm"
                )
            rects.append((x0, y0, x1, y1))
        spots = list(cells)
        for col, row in spots:
            if not self.grid.contains(col, row):
                raise ValueError(f"region {name!r}: cell ({col}, {row}) is outside the grid")
        rects += spans_to_rects(merge_cells(spots), self.grid.cell_cm)
        if not rects:
            raise ValueError(f"region {name!r} needs rect_cm=(x0, y0, x1, y1) or cells=[(col, row), ...]")
        self.regions[name] = Region(name, tuple(rects))
        self._rewrite()
        return self.regions[name]

    def save(self, path: str | Path) -> None:
        """Write the world as a YAML world file that `load_maze` (and `ev3sim2d run --maze`) reads back."""
        if self.text is None:
            self._rewrite()
        write_file(path, self.text)

    def _cell(self, cell: Cell | str) -> Cell:
        if isinstance(cell, Cell):
            return cell
        legend = self.grid.legend
        if len(cell) == 1 and legend is not None and cell in legend:
            return legend.cell(cell)
        found = cell_from_words(cell)
        if found is None:
            known = legend.describe() if legend is not None else ""
            raise ValueError(
                f"unknown cell {cell!r}; give a legend character ({known}), "
                "words like 'wall', 'green' or 'shade 40', or a Cell"
            )
        return found

    def _rewrite(self) -> None:
        """Bring `text` up to date with the grid, starts and regions, through the world file's writer (which
        changes only what changed), and take back what a file reader would make of it."""
        path = self.source or f"<world {self.name}>"
        if self.text is None:
            text = new_maze_text(
                self.grid.to_text(), cell_cm=self.grid.cell_cm, starts=self.starts, title=self.title
            )
        else:
            base = MazeSource(self.text, path)
            chars = base.chars
            cells = [
                [
                    EditedCell(cell, chars[row][col] if cell == base.grid.cell(col, row) else None)
                    for col, cell in ((col, self.grid.cell(col, row)) for col in range(self.grid.width))
                ]
                for row in range(self.grid.height)
            ]
            written = list(base.written_regions)
            added = [(name, list(r.rects)) for name, r in self.regions.items() if name not in base.regions]
            edited = EditedWorld(self.grid.cell_cm, cells, list(self.starts), written + added)
            text = write_maze_text(base, edited)
        again = read_maze(text, path)
        self.text, self.grid, self.regions, self.starts = (
            text,
            again["grid"],
            again["regions"],
            again["starts"],
        )
