"""`checkpoints`: the robot passes a list of places, in order (optionally all by a given time)."""

from __future__ import annotations

import numpy as np

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..place import read_places, validate_places
from ..run_record import RunRecord, seconds
from .reach_region import what

ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth", "tenth")


def ordinal(number: int) -> str:
    """'the second checkpoint' (words, so that a hidden variant's message holds no numbers)."""
    return f"the {ORDINALS[number - 1]} checkpoint" if number <= len(ORDINALS) else f"checkpoint {number}"


@register
class Checkpoints(Check):
    """Each place (a region, or a point with a radius; see docs/lessons.md) must be visited; with `in_order`
    (the default) each after the one before it; with `within_s` the last one by that time."""

    KIND = "checkpoints"
    SUMMARY = "the robot passes a list of places in order (by a given time, if given)"
    PARAMS = (
        Param("places", "list of places", "the places to pass: region names or points", read=read_places),
        Param("in_order", "bool", "whether they must be passed in the order given", default=True),
        Param("within_s", "seconds", "the last place must be reached by this simulated time", default=None),
        POINT_PARAM,
    )

    def validate(self, world, variant):
        validate_places(self, self.places, world, variant, "places")

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        who = what(self.point)
        order = " in order" if self.in_order and len(self.places) > 1 else ""
        if passed:
            return f"{who} passed every checkpoint{order}"
        return f"{who} did not pass every checkpoint{order}" + (
            " in time" if self.within_s is not None else ""
        )

    def evaluate(self, run: RunRecord) -> Outcome:
        track = run.track(self.point)
        who = what(self.point)
        row = 0
        times = []
        for number, place in enumerate(self.places, start=1):
            distance = place.distance(run, track)
            reached = np.flatnonzero(distance[row if self.in_order else 0 :] <= 0)
            if not len(reached):
                earlier = ""
                if len(times) == 1:
                    earlier = f"passed checkpoint 1 at {seconds(times[0])} but "
                elif times:
                    earlier = f"passed checkpoints 1 to {len(times)} (the last at {seconds(times[-1])}) but "
                rest = distance[row:] if self.in_order else distance
                closest = int(np.argmin(rest)) + (row if self.in_order else 0)
                after = " after that" if times and self.in_order else ""
                return Outcome(
                    False,
                    f"{who} {earlier}never reached checkpoint {number}, {place.describe()}{after}; the closest it "
                    f"came was {distance[closest]:.0f} cm away, at {seconds(float(run.t[closest]))}",
                    float(run.t[closest]),
                    f"{who} never reached {ordinal(number)}, {place.describe()}",
                )
            hit = int(reached[0]) + (row if self.in_order else 0)
            times.append(float(run.t[hit]))
            if self.in_order:
                row = hit
        last = max(times)
        if self.within_s is not None and last > self.within_s + 1e-9:
            return Outcome(
                False,
                f"{who} passed every checkpoint, but the last at {seconds(last)}, later than {self.within_s:g} s",
                last,
                f"{who} passed every checkpoint, but too late",
            )
        order = " in order" if self.in_order and len(self.places) > 1 else ""
        return Outcome(
            True,
            f"{who} passed all {len(self.places)} checkpoints{order}, the last at {seconds(last)}",
            last,
            f"{who} passed every checkpoint{order}",
        )
