"""`stop_in_region`: the run ends with the robot standing in a region."""

from __future__ import annotations

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..run_record import RunRecord, region_distance, seconds
from .reach_region import what


@register
class StopInRegion(Check):
    """At the end of the run the point (the centre by default) is in the region and the wheels are not driving."""

    KIND = "stop_in_region"
    SUMMARY = "the robot ends the run standing still in a region"
    PARAMS = (
        Param("region", "region", "name of the region in the world file"),
        Param("label", "text", "how messages name the region (default: 'the REGION')", default=None),
        POINT_PARAM,
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        name = self.label or f"the {self.region}"
        who = what(self.point)
        return f"{who} stopped in {name}" if passed else f"{who} did not stop in {name}"

    def evaluate(self, run: RunRecord) -> Outcome:
        name = self.label or f"the {self.region}"
        track = run.track(self.point)
        x, y = track[-1]
        end = run.end_s
        who = what(self.point)
        distance = float(region_distance(run.world, self.region, track[-1:])[0])
        if run.driving_at_end():
            return Outcome(
                False,
                f"the robot was still driving at the end ({seconds(end)}); stop the motors in {name}",
                end,
                f"the robot was still driving at the end; stop the motors in {name}",
            )
        stopped = run.last_moved_s()
        if distance <= 0:
            return Outcome(
                True, f"{who} stopped in {name} at {seconds(stopped)}", stopped, f"{who} stopped in {name}"
            )
        elsewhere = [other for other in run.world.regions_at(x, y) if other != self.region]
        where = f" in the {elsewhere[0]} region" if elsewhere else ""
        return Outcome(
            False,
            f"{who} stopped{where} at {seconds(stopped)}, {distance:.0f} cm from {name}",
            stopped,
            f"{who} stopped outside {name}",
        )
