"""`robot_contacts`: the robot touches other robots at most a number of times (never, by default)."""

from __future__ import annotations

import numpy as np

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds


@register
class RobotContacts(Check):
    """Counts the times the body comes into contact with another robot of the run (bumping into the
    robot ahead, being pushed); at most `max` pass."""

    KIND = "robot_contacts"
    SUMMARY = "the robot touches other robots at most N times (0 by default: never)"
    PASSES_WITHOUT_MOVING = True  # (unless another robot runs into it: still never a goal)
    PARAMS = (Param("max", "count", "the most contacts that pass (0: never touch another robot)", default=0),)

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        if self.max == 0:
            return "never touched another robot" if passed else "the robot touched another robot"
        return (
            "touched other robots, within what passes"
            if passed
            else "the robot touched other robots too often"
        )

    def evaluate(self, run: RunRecord) -> Outcome:
        touching = run.touching_robot
        starts = np.flatnonzero(touching[1:] & ~touching[:-1]) + 1
        count = len(starts)
        if count == 0:
            return Outcome(True, "never touched another robot", None, "never touched another robot")
        first = float(run.t[starts[0]])
        times = "once" if count == 1 else f"{count} times"
        if count > self.max:
            late = float(run.t[starts[self.max]])
            if self.max == 0:
                return Outcome(
                    False,
                    f"touched another robot {times}, first at {seconds(first)} (no contact passes)",
                    first,
                    "the robot touched another robot",
                )
            return Outcome(
                False,
                f"touched other robots {times}, the one too many at {seconds(late)} (at most {self.max} pass)",
                late,
                "the robot touched other robots too often",
            )
        return Outcome(
            True,
            f"touched another robot {times} (first at {seconds(first)}), within what passes",
            first,
            "touched other robots, within what passes",
        )
