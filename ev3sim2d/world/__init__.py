"""The world as pure data: grid of cells, maze files, regions, start poses and robot descriptions.

Nothing here knows about physics, rendering or programs; those layers read a `World`.
"""

from .cell import WALL, Cell
from .colors import EV3_COLORS, Ev3Color
from .grid import Grid
from .legend import DEFAULT_LEGEND, Legend, LegendEntry
from .maze_file import (
    find_maze,
    list_shipped_mazes,
    load_maze,
    maze_from_text_grid,
    parse_maze,
    shipped_mazes_dir,
)
from .pose import Pose
from .region import Region
from .robot_spec import BodySpec, MotorSpec, RobotSpec, SensorSpec, default_robot, load_robot
from .source_error import WorldFileError
from .world import World

__all__ = [
    "DEFAULT_LEGEND",
    "EV3_COLORS",
    "WALL",
    "BodySpec",
    "Cell",
    "Ev3Color",
    "Grid",
    "Legend",
    "LegendEntry",
    "MotorSpec",
    "Pose",
    "Region",
    "RobotSpec",
    "SensorSpec",
    "World",
    "WorldFileError",
    "default_robot",
    "find_maze",
    "list_shipped_mazes",
    "load_maze",
    "load_robot",
    "maze_from_text_grid",
    "parse_maze",
    "shipped_mazes_dir",
]
