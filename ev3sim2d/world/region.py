"""A named part of the floor (a goal, a start box, a colour patch) that lessons can ask about."""

from __future__ import annotations

from dataclasses import dataclass

from .rectangles import Rect


@dataclass(frozen=True)
class Region:
    """A name and the rectangles (x0, y0, x1, y1) in cm that make it up; edges as for cells."""

    name: str
    rects: tuple[Rect, ...]

    def contains(self, x_cm: float, y_cm: float) -> bool:
        """Whether the point lies in one of the rectangles (left/bottom edges in, right/top out)."""
        for x0, y0, x1, y1 in self.rects:
            if x0 <= x_cm < x1 and y0 <= y_cm < y1:
                return True
        return False

    def area_cm2(self) -> float:
        """Total area (the rectangles are expected not to overlap)."""
        return sum((x1 - x0) * (y1 - y0) for x0, y0, x1, y1 in self.rects)

    def center(self) -> tuple[float, float]:
        """The area-weighted centre of the rectangles, in cm."""
        area = self.area_cm2()
        if area <= 0:
            raise ValueError(f"region {self.name!r} has no area")
        x = sum((x1 - x0) * (y1 - y0) * (x0 + x1) / 2 for x0, y0, x1, y1 in self.rects) / area
        y = sum((x1 - x0) * (y1 - y0) * (y0 + y1) / 2 for x0, y0, x1, y1 in self.rects) / area
        return (x, y)

    def bounds(self) -> Rect:
        """The smallest rectangle around the whole region."""
        return (
            min(r[0] for r in self.rects),
            min(r[1] for r in self.rects),
            max(r[2] for r in self.rects),
            max(r[3] for r in self.rects),
        )

    def as_dict(self) -> dict[str, object]:
        """Plain values for traces and JSON."""
        return {"name": self.name, "rects": [list(rect) for rect in self.rects]}
