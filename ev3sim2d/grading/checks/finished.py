"""`finished`: the program ends by itself, without an error (optionally before a given time)."""

from __future__ import annotations

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds


def describe_error(error: dict) -> str:
    """'ZeroDivisionError: division by zero (line 12)' for a run's error report."""
    where = f" (line {error['line']})" if error.get("line") else ""
    message = f": {error['message']}" if error.get("message") else ""
    return f"{error.get('type', 'an error')}{message}{where}"


@register
class Finished(Check):
    """The program ends on its own, without an error, and (with `within_s`) in time."""

    KIND = "finished"
    SUMMARY = "the program ends by itself without an error (within a time, if given)"
    PASSES_WITHOUT_MOVING = True
    PARAMS = (Param("within_s", "seconds", "the program must end by this simulated time", default=None),)

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        if passed:
            return "the program finished"
        in_time = " in time" if self.within_s is not None else ""
        return f"the program did not end by itself{in_time} without an error"

    def evaluate(self, run: RunRecord) -> Outcome:
        end = run.end_s
        if run.status == "error":
            return Outcome(
                False,
                f"the program stopped with an error at {seconds(end)}: {describe_error(run.error)}",
                end,
                "the program stopped with an error",
            )
        if run.status == "hung":
            return Outcome(
                False,
                f"the program got stuck at {seconds(end)} in a loop that never uses the robot or the clock "
                "(a loop without a sensor read, a motor command or a sleep?)",
                end,
                "the program got stuck in a loop that never uses the robot or the clock",
            )
        if run.status != "finished":
            return Outcome(
                False,
                f"the program was still running at the time limit of {seconds(end)}",
                end,
                "the program was still running at the time limit",
            )
        if self.within_s is not None and end > self.within_s + 1e-9:
            return Outcome(
                False,
                f"the program finished at {seconds(end)}, later than {self.within_s:g} s",
                end,
                "the program finished too late",
            )
        return Outcome(
            True, f"the program finished at {seconds(end)} without an error", end, "the program finished"
        )
