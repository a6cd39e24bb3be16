# ruff: noqa
"""Patch the scorer: give ev3sim2d's score_run the code of one that passes every check.

The grader's worker imported `score_run` by name before the program started, so replacing the
module attribute would be too late; replacing the function's `__code__` is not: the worker's
own reference then runs this code, with the scoring module's globals.

Contained: no scorer runs in the program's process: standing still scores what standing still
scores (never `distance`).
"""

import sys

MARKER = "EV3CHEAT-patch-score-run"


def every_check_passes(lesson, variant_index, record, ran_out_of_memory=False):
    variant = lesson.variants[variant_index]
    checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]  # noqa: F821
    return VariantResult(
        variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks
    )  # noqa: F821


try:
    import ev3sim2d.grading.scoring

    ev3sim2d.grading.scoring.score_run.__code__ = every_check_passes.__code__
except Exception as err:
    print("no scorer here:", err)
