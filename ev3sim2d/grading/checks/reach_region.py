"""`reach_region`: the robot gets into a region (optionally by a given time)."""

from __future__ import annotations

import numpy as np

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..run_record import RunRecord, region_distance, seconds


def what(point: str) -> str:
    """How a message names the point of the robot that counts."""
    return {"centre": "the robot", "color-sensor": "the colour sensor", "front": "the robot's front"}[point]


@register
class ReachRegion(Check):
    """Some point of the robot (its centre by default) is inside the region at some time, by `within_s` if given."""

    KIND = "reach_region"
    SUMMARY = "the robot gets into a region of the world (by a given time, if given)"
    PARAMS = (
        Param("region", "region", "name of the region in the world file"),
        Param("within_s", "seconds", "the region must be reached by this simulated time", default=None),
        Param("label", "text", "how messages name the region (default: 'the REGION')", default=None),
        POINT_PARAM,
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        name = self.label or f"the {self.region}"
        who = what(self.point)
        if passed:
            return f"{who} reached {name}"
        return (
            f"{who} never reached {name}" if self.within_s is None else f"{who} did not reach {name} in time"
        )

    def evaluate(self, run: RunRecord) -> Outcome:
        name = self.label or f"the {self.region}"
        distance = region_distance(run.world, self.region, run.track(self.point))
        inside = np.flatnonzero(distance <= 0)
        who = what(self.point)
        if len(inside):
            t = float(run.t[inside[0]])
            if self.within_s is not None and t > self.within_s + 1e-9:
                return Outcome(
                    False,
                    f"{who} reached {name} at {seconds(t)}, later than {self.within_s:g} s",
                    t,
                    f"{who} reached {name}, but too late",
                )
            return Outcome(True, f"{who} reached {name} at {seconds(t)}", t, f"{who} reached {name}")
        closest = int(np.argmin(distance))
        t = float(run.t[closest])
        return Outcome(
            False,
            f"{who} never reached {name}; the closest it came was {distance[closest]:.0f} cm away, at {seconds(t)}",
            t,
            f"{who} never reached {name}",
        )
