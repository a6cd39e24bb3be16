"""A world as read from a maze file: the grid, where robots start, named regions and the robots to build."""

from __future__ import annotations

from dataclasses import dataclass, field

from .button_press import ButtonPress
from .grid import Grid
from .pose import Pose
from .region import Region
from .robot_spec import RobotSpec

DEFAULT_AMBIENT = 10.0
"""Ambient light (0..100) when a world file gives none: a lit classroom as the EV3 sees it."""


@dataclass
class World:
    """Everything a maze file says; `source` is its path and `text` its YAML (both None when built in code)."""

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
