# ruff: noqa
"""The helper as compiled into the smuggled pyc (left out of the hand-in: the test compiles it)."""

MARKER = "EV3CHEAT-pyc-smuggle"


def every_check_passes(lesson, variant_index, record, ran_out_of_memory=False):
    variant = lesson.variants[variant_index]
    checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]  # noqa: F821
    return VariantResult(
        variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks
    )  # noqa: F821


try:
    import ev3sim2d.grading.scoring

    ev3sim2d.grading.scoring.score_run.__code__ = every_check_passes.__code__
except Exception:
    pass


def say_hello():
    print("hello from the helper")
