"""A place a check asks about: a named region of the world, a point in it, or a point relative to the start.

In a lesson file a place is written as a region name (`goal`), or a mapping:
`{region: goal}`, `{at: [120, 40], radius_cm: 10}` (world cm), or
`{from_start: [50, 0], radius_cm: 8}` (cm ahead of and to the left of where the
robot starts, so the place moves with a variant's start).  `label` names it
in messages ("the first corner").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..world.world import World
from ..world.yaml_source import Node
from .run_record import RunRecord, region_distance

PLACE_KEYS = ("region", "at", "from_start", "radius_cm", "label")
PLACE_EXAMPLE = "{from_start: [50, 0], radius_cm: 8, label: the first corner}"
DEFAULT_RADIUS_CM = 10.0


@dataclass(frozen=True)
class Place:
    """Exactly one of `region`, `at` or `from_start`; points count as reached within `radius_cm`."""

    region: str | None = None
    at: tuple[float, float] | None = None
    from_start: tuple[float, float] | None = None
    radius_cm: float = DEFAULT_RADIUS_CM
    label: str | None = None

    def describe(self) -> str:
        if self.label:
            return self.label
        if self.region is not None:
            return f"the {self.region} region"
        if self.at is not None:
            return f"the point ({self.at[0]:g}, {self.at[1]:g}) cm"
        forward, left = self.from_start or (0.0, 0.0)
        if forward == 0 and left == 0:
            return "the start"
        parts = []
        if forward:
            parts.append(f"{abs(forward):g} cm {'ahead of' if forward > 0 else 'behind'}")
        if left:
            parts.append(f"{abs(left):g} cm {'left of' if left > 0 else 'right of'}")
        return "the point " + " and ".join(parts) + " the start"

    def point(self, run: RunRecord) -> tuple[float, float] | None:
        """The place as a world point (None for a region)."""
        if self.at is not None:
            return self.at
        if self.from_start is not None:
            return run.from_start(*self.from_start)
        return None

    def distance(self, run: RunRecord, xy: np.ndarray) -> np.ndarray:
        """How far each point is from the place: 0 inside the region or within the radius."""
        if self.region is not None:
            return region_distance(run.world, self.region, xy)
        px, py = self.point(run)
        return np.maximum(np.hypot(xy[:, 0] - px, xy[:, 1] - py) - self.radius_cm, 0.0)

    def center_distance(self, run: RunRecord, xy: np.ndarray) -> np.ndarray:
        """Distance to the point itself (to the region, for a region)."""
        if self.region is not None:
            return region_distance(run.world, self.region, xy)
        px, py = self.point(run)
        return np.hypot(xy[:, 0] - px, xy[:, 1] - py)

    def region_names(self) -> list[str]:
        return [self.region] if self.region is not None else []


def read_place(node: Node, name: str = "place") -> Place:
    """A place from YAML (see the module docstring)."""
    if node.is_scalar and not node.is_null:
        return Place(region=node.as_text(name).strip())
    if not node.is_mapping:
        raise node.error(
            f"'{name}' is a region name or a mapping like `{PLACE_EXAMPLE}`, got {node.describe()}"
        )
    fields = node.as_fields(name, PLACE_KEYS, PLACE_EXAMPLE)
    given = [key for key in ("region", "at", "from_start") if key in fields]
    if len(given) != 1:
        raise node.error(
            f"a place needs exactly one of `region: NAME`, `at: [x, y]` or `from_start: [forward, left]`"
            f"{'; got ' + ', '.join(given) if given else ''}",
            column=False,
        )
    label = fields.text("label", default=None)
    radius = fields.number("radius_cm", default=DEFAULT_RADIUS_CM, unit="cm", example="radius_cm: 10")
    if radius < 0:
        raise fields.get("radius_cm").error("'radius_cm' cannot be negative")
    if "region" in fields:
        return Place(region=fields.text("region").strip(), label=label)
    if "at" in fields:
        x, y = fields.get("at").as_numbers("at", 2, "cm", "at: [120, 40]")
        return Place(at=(x, y), radius_cm=radius, label=label)
    forward, left = fields.get("from_start").as_numbers("from_start", 2, "cm", "from_start: [50, 0]")
    return Place(from_start=(forward, left), radius_cm=radius, label=label)


def read_places(node: Node) -> tuple[Place, ...]:
    """A non-empty list of places."""
    items = node.as_list("places", f"places: [goal, {PLACE_EXAMPLE}]")
    if not items:
        raise node.error("'places' needs at least one place")
    return tuple(read_place(item, "places") for item in items)


def validate_places(
    check, places: tuple[Place, ...] | list[Place], world: World, variant: str, param: str
) -> None:
    """Each region a place names must be in the world."""
    for place in places:
        for region in place.region_names():
            check.require_region(world, variant, param, region)
