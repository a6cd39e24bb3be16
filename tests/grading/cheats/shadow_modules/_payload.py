# ruff: noqa
"""What each shadowing module runs when it is imported: note who imported it, and give full marks if it can."""

import os
import sys

MARKER = "EV3CHEAT-shadow-modules"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"


def every_check_passes(lesson, variant_index, record, ran_out_of_memory=False):
    variant = lesson.variants[variant_index]
    checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]  # noqa: F821
    return VariantResult(
        variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks
    )  # noqa: F821


def strike(name):
    try:
        os.makedirs(DROP_DIR, exist_ok=True)
        with open(os.path.join(DROP_DIR, f"shadow_modules-{name}-{os.getpid()}.txt"), "w") as f:
            f.write(" ".join(sys.argv))
    except OSError:
        pass
    scoring = sys.modules.get("ev3sim2d.grading.scoring")
    if scoring is not None:
        scoring.score_run.__code__ = every_check_passes.__code__


def stand_in(name, here):
    """Import the real module `name` (without the student's folder on sys.path) and put it in sys.modules."""
    import importlib

    saved = sys.path[:]
    sys.path[:] = [p for p in sys.path if os.path.abspath(p or ".") != here]
    shadow = sys.modules.pop(name, None)
    try:
        sys.modules[name] = importlib.import_module(name)
    except ImportError:
        if shadow is not None:
            sys.modules[name] = shadow
    finally:
        sys.path[:] = saved
