"""`end_near`: the robot ends the run within a distance of a place (the start, by default)."""

from __future__ import annotations

import math

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..place import Place, read_place, validate_places
from ..run_record import RunRecord
from .reach_region import what


@register
class EndNear(Check):
    """The point's distance at the end of the run to `place` is at most `within_cm`, after the robot has
    travelled at least `min_path_cm` (so that, as a goal, ending where it started is not passed by standing still)."""

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
        Param("min_path_cm", "cm", "how far the robot must have travelled before", default=0.0),
        POINT_PARAM,
    )

    def passes_without_moving(self) -> bool:
        """A place near the start passes a robot that stands still, unless it must travel first."""
        if self.min_path_cm > 0 or self.place.from_start is None:
            return False
        return math.hypot(*self.place.from_start) <= self.within_cm

    def validate(self, world, variant):
        validate_places(self, [self.place], world, variant, "place")

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        who, name = what(self.point), self.place.describe()
        return f"{who} ended at {name}" if passed else f"{who} did not end at {name}"

    def evaluate(self, run: RunRecord) -> Outcome:
        end = run.end_s
        distance = float(self.place.center_distance(run, run.track(self.point)[-1:])[0])
        name = self.place.describe()
        who = what(self.point)
        travelled = run.path_cm
        if travelled + 1e-9 < self.min_path_cm:
            return Outcome(
                False,
                f"the robot travelled only {travelled:.0f} cm (at least {self.min_path_cm:g} cm before ending at "
                f"{name})",
                end,
                "the robot did not travel far enough",
            )
        if distance <= self.within_cm + 1e-9:
            return Outcome(True, f"{who} ended {distance:.1f} cm from {name}", end, f"{who} ended at {name}")
        return Outcome(
            False,
            f"{who} ended {distance:.1f} cm from {name} (at most {self.within_cm:g} cm passes)",
            end,
            f"{who} ended too far from {name}",
        )
