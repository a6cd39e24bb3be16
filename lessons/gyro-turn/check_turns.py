"""A check kind of this lesson: `turns`, the robot turns on the spot by given angles, pausing after each.

An example of a lesson's own check: a Check subclass with a KIND, in a check_*.py file next to
lesson.yaml.  It reads only the run's record (the trace and the world), and says what it found twice:
in full, and without numbers (`brief`, shown for hidden variants).
"""

from __future__ import annotations

import numpy as np

from ev3sim2d.grading.check import Check, Outcome, Param
from ev3sim2d.grading.run_record import RunRecord, seconds

ORDINALS = ("first", "second", "third", "fourth", "fifth", "sixth")


def read_angles(node) -> tuple[float, ...]:
    items = node.as_list("angles_deg", "angles_deg: [90, 180, 270]")
    if not items:
        raise node.error("'angles_deg' needs at least one angle, e.g. `angles_deg: [90, 180, 270]`")
    return tuple(item.as_number("angles_deg", "degrees, to the right") for item in items)


def rests(run: RunRecord, pause_s: float) -> list[tuple[int, int]]:
    """(first, last) rows of each stretch of at least pause_s in which the robot stood still."""
    still = np.concatenate(
        [[True], (np.abs(np.diff(run.heading_deg)) < 1e-3) & (run.step_lengths()[1:] < 1e-3)]
    )
    edges = np.diff(np.concatenate([[0], still.astype(int), [0]]))
    found = []
    for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1, strict=True):
        if a == 0 or run.t[b] - run.t[a] >= pause_s:
            found.append((int(a), int(b)))
    last = len(still) - 1
    if not found or found[-1][1] != last:  # where the robot ended is a rest too
        found.append((last, last))
    return found


class Turns(Check):
    """Between the robot's pauses (standing still at least `pause_s`), it turns by `angles_deg`
    (to the right, in order), each within `within_deg`."""

    KIND = "turns"
    SUMMARY = "the robot turns by the given angles to the right, pausing after each"
    PARAMS = (
        Param("angles_deg", "list of degrees", "the turns to make, to the right", read=read_angles),
        Param("within_deg", "degrees", "the largest error that passes, per turn", default=3.0),
        Param("pause_s", "seconds", "how long the robot stands still between turns", default=0.5),
    )

    def evaluate(self, run: RunRecord) -> Outcome:
        headings = []
        times = []
        for a, b in rests(run, self.pause_s):
            heading = float(run.heading_deg[b])
            if headings and abs(heading - headings[-1]) < 0.5:
                continue  # a pause where it already was: not a turn
            headings.append(heading)
            times.append(float(run.t[a]))
        turns = [-(b - a) for a, b in zip(headings, headings[1:], strict=False)]  # to the right
        made = ", ".join(f"{t:.1f}°" for t in turns) or "none"
        for i, wanted in enumerate(self.angles_deg):
            if i >= len(turns):
                return Outcome(
                    False,
                    f"{self._count(turns, made)}; pause {self.pause_s:g} s after each turn",
                    run.end_s,
                    "made too few turns, or did not pause after each",
                )
            if abs(turns[i] - wanted) > self.within_deg + 1e-9:
                which = ORDINALS[i] if i < len(ORDINALS) else f"turn {i + 1}"
                return Outcome(
                    False,
                    f"the {which} turn, ending at {seconds(times[i + 1])}, was {turns[i]:.1f}° to the right, "
                    f"not {wanted:g}° (±{self.within_deg:g}°)",
                    times[i + 1],
                    f"the {which} turn was not exact",
                )
        if len(turns) > len(self.angles_deg):
            return Outcome(False, self._count(turns, made), run.end_s, "made too many turns")
        return Outcome(
            True,
            f"turned {made} to the right, each within {self.within_deg:g}°",
            times[-1],
            "turned by each angle",
        )

    def _count(self, turns: list[float], made: str) -> str:
        wanted = len(self.angles_deg)
        return f"made {len(turns)} turn{'' if len(turns) == 1 else 's'} ({made}), not {wanted}"
