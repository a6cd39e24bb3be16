"""`end_near`: the robot ends the run within a distance of a place (the start, by default)."""

from __future__ import annotations

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..place import Place, read_place, validate_places
from ..run_record import RunRecord
from .reach_region import what


@register
class EndNear(Check):
    """The point's distance at the end of the run to `place` is at most `within_cm`."""

    KIND = "end_near"
    SUMMARY = "the robot ends the run within a distance of a place (the start by default)"
    PARAMS = (
        Param(
            "place",
            "place",
            "where to end: a region name, {at: [x, y]} or {from_start: [forward, left]} (default: the start)",
            default=Place(from_start=(0.0, 0.0)),
            read=read_place,
        ),
        Param("within_cm", "cm", "the largest distance that passes", default=5.0),
        POINT_PARAM,
    )

    def validate(self, world, variant):
        validate_places(self, [self.place], world, variant, "place")

    def evaluate(self, run: RunRecord) -> Outcome:
        end = run.end_s
        distance = float(self.place.center_distance(run, run.track(self.point)[-1:])[0])
        name = self.place.describe()
        if distance <= self.within_cm + 1e-9:
            return Outcome(True, f"{what(self.point)} ended {distance:.1f} cm from {name}", end)
        return Outcome(
            False,
            f"{what(self.point)} ended {distance:.1f} cm from {name} (at most {self.within_cm:g} cm passes)",
            end,
        )
