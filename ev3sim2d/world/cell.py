"""One square of the world: a wall, or floor painted a grey shade or an EV3 colour.

A cell answers what a downward colour sensor reads on it; the answers are
computed once, because sensors ask them every tick.  A wall blocks robots and
ultrasonic rays; its colour (dark grey unless given) is only what a sensor
looking down onto its top would see and what the renderer draws.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .colors import EV3_COLORS, shade_color_id, shade_display_rgb, shade_raw_rgb, shade_reflected

WALL_SHADE = 25.0
"""The grey of a wall given no colour of its own."""


@dataclass(frozen=True, slots=True)
class Cell:
    """A wall or a floor square; floor has exactly one of `shade` (0 black .. 100 white) or `color`."""

    wall: bool = False
    shade: float | None = None
    color: str | None = None
    reflected: float = field(init=False, repr=False, compare=False)
    color_id: int = field(init=False, repr=False, compare=False)
    raw_rgb: tuple[float, float, float] = field(init=False, repr=False, compare=False)
    display_rgb: tuple[int, int, int] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.shade is not None and self.color is not None:
            raise ValueError(f"a cell has a shade or a colour, not both: {self!r}")
        if not self.wall and self.shade is None and self.color is None:
            raise ValueError("a floor cell needs a shade or a colour")
        if self.shade is not None and not 0 <= self.shade <= 100:
            raise ValueError(f"shade must be 0..100, got {self.shade}")
        if self.color is not None and self.color not in EV3_COLORS:
            raise ValueError(f"unknown colour {self.color!r}; known: {', '.join(EV3_COLORS)}")
        if self.color is not None:
            ev3 = EV3_COLORS[self.color]
            answers = (ev3.reflected, ev3.id, ev3.raw_rgb, ev3.display_rgb)
        else:
            shade = WALL_SHADE if self.shade is None else self.shade
            answers = (
                shade_reflected(shade),
                shade_color_id(shade),
                shade_raw_rgb(shade),
                shade_display_rgb(shade),
            )
        for name, value in zip(("reflected", "color_id", "raw_rgb", "display_rgb"), answers, strict=True):
            object.__setattr__(self, name, value)

    @classmethod
    def floor_shade(cls, shade: float) -> Cell:
        """Grey floor, 0 black .. 100 white."""
        return cls(wall=False, shade=float(shade))

    @classmethod
    def floor_color(cls, color: str) -> Cell:
        """Floor painted one of the EV3 colours."""
        return cls(wall=False, color=color)

    def describe(self) -> str:
        """Short words for messages and logs: 'wall', 'shade 40', 'red'."""
        paint = self.color or (f"shade {self.shade:g}" if self.shade is not None else "")
        if self.wall:
            return f"wall ({paint})" if paint else "wall"
        return paint


WALL = Cell(wall=True)
"""A plain dark-grey wall."""

WHITE_FLOOR = Cell.floor_shade(100)
"""The usual floor."""
