"""`lap`: the robot goes away from its start and comes back to it (optionally by a given time)."""

from __future__ import annotations

import numpy as np

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds


@register
class Lap(Check):
    """A lap: the robot's centre gets at least `min_away_cm` from its start, has travelled at least
    `min_path_cm`, and then comes back within `radius_cm` of the start; by `within_s` if given."""

    KIND = "lap"
    SUMMARY = "the robot goes round and comes back to where it started (by a given time, if given)"
    PARAMS = (
        Param("radius_cm", "cm", "how close to the start counts as back", default=15.0),
        Param("min_away_cm", "cm", "how far from the start the robot must have been", default=50.0),
        Param("min_path_cm", "cm", "how far the robot must have travelled before it is back", default=0.0),
        Param("within_s", "seconds", "the lap must be complete by this simulated time", default=None),
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        if passed:
            return "completed a lap"
        return "did not complete a lap" + (" in time" if self.within_s is not None else "")

    def evaluate(self, run: RunRecord) -> Outcome:
        x0, y0, _ = run.start
        xy = run.xy
        distance = np.hypot(xy[:, 0] - x0, xy[:, 1] - y0)
        travelled = np.cumsum(run.step_lengths())
        away = np.flatnonzero(distance >= self.min_away_cm)
        end = run.end_s
        if not len(away):
            return Outcome(
                False,
                f"did not go round: the robot never got {self.min_away_cm:g} cm from its start "
                f"(at most {distance.max():.0f} cm)",
                end,
                "did not go round: the robot never got far enough from its start",
            )
        back = np.flatnonzero((distance <= self.radius_cm) & (travelled >= self.min_path_cm))
        back = back[back > away[0]]
        if not len(back):
            return Outcome(
                False,
                f"did not come back to the start by {seconds(end)} (it travelled {travelled[-1]:.0f} cm and "
                f"ended {distance[-1]:.0f} cm from the start)",
                end,
                "did not come back to the start",
            )
        t = float(run.t[back[0]])
        if self.within_s is not None and t > self.within_s + 1e-9:
            return Outcome(
                False,
                f"completed a lap at {seconds(t)}, later than {self.within_s:g} s",
                t,
                "completed a lap, but too late",
            )
        return Outcome(True, f"completed a lap at {seconds(t)}", t, "completed a lap")
