"""`avoid_region`: the robot never enters a region (a danger zone, a side line it must not take)."""

from __future__ import annotations

import numpy as np

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..run_record import RunRecord, region_inside, seconds
from .reach_region import what


@register
class AvoidRegion(Check):
    """The point (the centre by default) is never inside the region."""

    KIND = "avoid_region"
    SUMMARY = "the robot never enters a region of the world"
    PASSES_WITHOUT_MOVING = True
    PARAMS = (
        Param("region", "region", "name of the region in the world file"),
        Param("label", "text", "how messages name the region (default: 'the REGION')", default=None),
        POINT_PARAM,
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        name = self.label or f"the {self.region}"
        return f"{what(self.point)} {'kept out of' if passed else 'went into'} {name}"

    def evaluate(self, run: RunRecord) -> Outcome:
        name = self.label or f"the {self.region}"
        inside = np.flatnonzero(region_inside(run.world, self.region, run.track(self.point)))
        if len(inside):
            t = float(run.t[inside[0]])
            return Outcome(
                False,
                f"{what(self.point)} went into {name} at {seconds(t)}",
                t,
                f"{what(self.point)} went into {name}",
            )
        return Outcome(
            True, f"{what(self.point)} kept out of {name}", None, f"{what(self.point)} kept out of {name}"
        )
