"""`wall_contacts`: the robot touches walls at most a number of times (and for at most a time)."""

from __future__ import annotations

import numpy as np

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds


@register
class WallContacts(Check):
    """Counts the times the body comes into contact with a wall; at most `max` pass, and, with
    `max_touch_s`, the total time touching must not exceed it (pushing along a wall)."""

    KIND = "wall_contacts"
    SUMMARY = "the robot touches walls at most N times (0 by default), for at most a total time if given"
    PASSES_WITHOUT_MOVING = True
    PARAMS = (
        Param("max", "count", "the most contacts that pass (0: never touch a wall)", default=0),
        Param("max_touch_s", "seconds", "the longest total time touching walls that passes", default=None),
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        if self.max == 0 and self.max_touch_s is None:
            return "never touched a wall" if passed else "the robot touched a wall"
        return "touched walls, within what passes" if passed else "the robot touched walls more than passes"

    def evaluate(self, run: RunRecord) -> Outcome:
        touching = run.touching
        starts = np.flatnonzero(touching[1:] & ~touching[:-1]) + 1
        count = len(starts)
        dt = np.diff(run.t)
        touch_s = float(dt[touching[1:]].sum()) if len(dt) else 0.0
        if count == 0:
            return Outcome(True, "never touched a wall", None, "never touched a wall")
        first = float(run.t[starts[0]])
        times = "once" if count == 1 else f"{count} times"
        if count > self.max:
            limit = "no contact passes" if self.max == 0 else f"at most {self.max} pass"
            late = float(run.t[starts[self.max]])
            moment = f"first at {seconds(first)}" if self.max == 0 else f"the one too many at {seconds(late)}"
            brief = "the robot touched a wall" if self.max == 0 else "the robot touched walls too often"
            return Outcome(False, f"touched a wall {times}, {moment} ({limit})", late, brief)
        if self.max_touch_s is not None and touch_s > self.max_touch_s + 1e-9:
            return Outcome(
                False,
                f"touched walls for {touch_s:.1f} s in all, from {seconds(first)} (at most {self.max_touch_s:g} s passes)",
                first,
                "the robot touched walls for too long",
            )
        return Outcome(
            True,
            f"touched a wall {times} (first at {seconds(first)}), within what passes",
            first,
            "touched walls, within what passes",
        )
