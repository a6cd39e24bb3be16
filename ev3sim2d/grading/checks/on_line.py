"""`on_line`: the colour sensor stays over the line (the dark cells of the floor) for most of the path."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..check import POINT_PARAM, Check, Outcome, Param, register
from ..run_record import RunRecord, region_inside, seconds
from ..world_geometry import distance_to_cells, line_cells


def off_stretches(on: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) row of each run of consecutive False values."""
    off = ~on
    edges = np.diff(np.concatenate([[0], off.astype(int), [0]]))
    return list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1, strict=True))


@register
class OnLine(Check):
    """The spot the colour sensor sees is over the line (within `tolerance_cm` of a cell darker than
    `darker_than`) for at least `min_fraction` of the distance it travels, and, with `max_off_s`, is never
    off it for longer than that.  Cells of the `gaps` region count as line."""

    KIND = "on_line"
    SUMMARY = "the colour sensor stays over the line for a fraction of its path, never off it for long"
    PARAMS = (
        Param(
            "min_fraction",
            "fraction",
            "the smallest fraction of the path over the line that passes",
            default=0.9,
        ),
        Param("max_off_s", "seconds", "the longest time off the line that passes", default=None),
        Param("tolerance_cm", "cm", "how far from a line cell still counts as over the line", default=2.0),
        Param(
            "darker_than", "number", "cells with less reflected light than this are the line", default=40.0
        ),
        Param("gaps", "region", "a region (gaps in the line) that counts as line", default=None),
        Param("from_s", "seconds", "start judging at this time", default=0.0),
        Param(
            "until_region",
            "region",
            "stop judging when the robot first comes back into this region "
            "after leaving it (e.g. the end of a lap)",
            default=None,
        ),
        replace(POINT_PARAM, default="color-sensor"),
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        return "stayed over the line" if passed else "did not stay over the line"

    def evaluate(self, run: RunRecord) -> Outcome:
        track = run.track(self.point)
        grid = run.world.grid
        on = (
            distance_to_cells(grid, line_cells(grid, self.darker_than), track, self.tolerance_cm)
            <= self.tolerance_cm
        )
        if self.gaps is not None:
            on |= region_inside(run.world, self.gaps, track)
        steps = run.step_lengths(self.point)
        first = run.index_at(self.from_s)
        last = self._last_row(run)
        on, steps, t = on[first : last + 1], steps[first : last + 1], run.t[first : last + 1]
        path = float(steps[1:].sum())
        if path < 1.0:
            return Outcome(
                False,
                "the robot hardly moved, so it did not follow the line",
                float(t[-1]),
                "the robot hardly moved, so it did not follow the line",
            )
        fraction = float(steps[1:][on[1:]].sum()) / path
        stretches = off_stretches(on)
        end_s = float(t[-1])
        if stretches:
            a, b = stretches[-1]
            lost_s = float(t[b] - t[a])
            limit = self.max_off_s if self.max_off_s is not None else 2.0
            if b == len(on) - 1 and lost_s > limit:
                return Outcome(
                    False,
                    f"left the line at {seconds(float(t[a]))} and did not find it again",
                    float(t[a]),
                    "left the line and did not find it again",
                )
        if self.max_off_s is not None and stretches:
            longest = max(stretches, key=lambda ab: t[ab[1]] - t[ab[0]])
            a, b = longest
            length = float(t[b] - t[a])
            if length > self.max_off_s + 1e-9:
                return Outcome(
                    False,
                    f"was off the line from {seconds(float(t[a]))} to {seconds(float(t[b]))} "
                    f"({length:.1f} s; at most {self.max_off_s:g} s passes)",
                    float(t[a]),
                    "was off the line for too long",
                )
        if fraction + 1e-9 < self.min_fraction:
            a = stretches[0][0] if stretches else 0
            return Outcome(
                False,
                f"was over the line for only {fraction:.0%} of its path (at least {self.min_fraction:.0%} passes); "
                f"it first left it at {seconds(float(t[a]))}",
                float(t[a]),
                "was over the line for too little of its path",
            )
        return Outcome(
            True,
            f"was over the line for {fraction:.0%} of its path, until {seconds(end_s)}",
            end_s,
            "stayed over the line",
        )

    def _last_row(self, run: RunRecord) -> int:
        if self.until_region is None:
            return len(run.t) - 1
        inside = region_inside(run.world, self.until_region, run.xy)
        left = np.flatnonzero(~inside)
        if not len(left):
            return len(run.t) - 1
        back = np.flatnonzero(inside[left[0] :])
        return int(left[0] + back[0]) if len(back) else len(run.t) - 1
