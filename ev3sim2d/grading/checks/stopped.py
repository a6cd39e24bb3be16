"""`stopped`: the robot stands still at the end of the run (its motors stopped, not left driving)."""

from __future__ import annotations

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds


@register
class Stopped(Check):
    """At the end of the run the wheel motors are not driving (on a real EV3 they would go on after
    the program ends); with `by_s`, the robot must have stood still since that time."""

    KIND = "stopped"
    SUMMARY = "the robot stands still at the end of the run, its motors stopped (by a given time, if given)"
    PARAMS = (Param("by_s", "seconds", "the robot must not move after this simulated time", default=None),)
    PASSES_WITHOUT_MOVING = True

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        if passed:
            return "the robot stopped"
        return "the robot did not stop" + (" in time" if self.by_s is not None else "")

    def evaluate(self, run: RunRecord) -> Outcome:
        end = run.end_s
        if run.driving_at_end():
            return Outcome(
                False,
                f"the motors were still driving when the run ended at {seconds(end)} "
                "(a real robot would drive on: stop the motors)",
                end,
                "the motors were still driving when the run ended",
            )
        last = run.last_moved_s()
        if self.by_s is not None and last > self.by_s + 1e-9:
            return Outcome(
                False,
                f"the robot last moved at {seconds(last)}, later than {self.by_s:g} s",
                last,
                "the robot stopped too late",
            )
        return Outcome(True, f"the robot stopped at {seconds(last)}", last, "the robot stopped")
