"""`end_heading`: the robot ends the run facing a given direction, within a tolerance."""

from __future__ import annotations

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord


def angle_between(a_deg: float, b_deg: float) -> float:
    """The signed smallest turn from b to a, -180..180 degrees (counter-clockwise positive)."""
    return (a_deg - b_deg + 180.0) % 360.0 - 180.0


@register
class EndHeading(Check):
    """The final heading is `heading_deg` (world, 0 = +x, counter-clockwise), or the start heading turned by
    `from_start_deg` (counter-clockwise positive: -90 is a quarter turn to the right), within `within_deg`."""

    KIND = "end_heading"
    SUMMARY = "the robot ends the run facing a direction (absolute, or turned from its start heading)"
    PARAMS = (
        Param("heading_deg", "degrees", "the wanted world heading (0 = +x, 90 = +y)", default=None),
        Param(
            "from_start_deg",
            "degrees",
            "or: the wanted turn from the start heading, counter-clockwise (-90 = a right turn); default 0",
            default=None,
        ),
        Param("within_deg", "degrees", "the largest difference that passes", default=5.0),
    )

    def wanted_name(self) -> str:
        """The wanted heading in words, from the check's parameters alone."""
        if self.heading_deg is not None:
            return f"a heading of {self.heading_deg:g}°"
        turn = self.from_start_deg or 0.0
        if turn == 0:
            return "its start heading"
        return f"{abs(turn):g}° {'left' if turn > 0 else 'right'} of its start heading"

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        name = self.wanted_name()
        return f"ended facing {name}" if passed else f"did not end facing {name}"

    def evaluate(self, run: RunRecord) -> Outcome:
        final = float(run.heading_deg[-1])
        name = self.wanted_name()
        if self.heading_deg is not None:
            wanted = self.heading_deg
        else:
            wanted = run.start[2] + (self.from_start_deg or 0.0)
        off = angle_between(final, wanted)
        side = "left" if off > 0 else "right"
        end = run.end_s
        if abs(off) <= self.within_deg + 1e-9:
            return Outcome(True, f"ended facing {abs(off):.1f}° from {name}", end, f"ended facing {name}")
        return Outcome(
            False,
            f"ended facing {abs(off):.1f}° to the {side} of {name} (at most {self.within_deg:g}° passes)",
            end,
            f"ended facing too far to the {side} of {name}",
        )
