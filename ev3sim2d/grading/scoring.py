"""Score one run of one variant: every check of the lesson on the run's record, or none if there was no run."""

from __future__ import annotations

from .checks.finished import describe_error
from .lesson import Lesson
from .result import CheckResult, VariantResult
from .run_record import RunRecord, seconds

RUN_STATUS = {
    "finished": "graded",
    "time_limit": "graded",
    "error": "error",
    "hung": "timeout",
    "interrupted": "error",
}


def run_message(record: RunRecord, status: str, memory_mb: float) -> str:
    """How the run ended, in a sentence for students."""
    end = seconds(record.end_s)
    error = record.error or {}
    if status == "memory":
        return (
            f"the program ran out of memory at {end} (it may use {memory_mb:g} MB); line {error.get('line')}"
        )
    if record.status == "error":
        return f"the program stopped with an error at {end}: {describe_error(error)}"
    if record.status == "hung":
        return f"the program got stuck at {end} in a loop that never uses the robot or the clock, so it was stopped"
    if record.status == "time_limit":
        return f"the program ran until the time limit of {end}"
    return f"the program finished at {end}"


def score_run(
    lesson: Lesson, variant_index: int, record: RunRecord, ran_out_of_memory: bool = False
) -> VariantResult:
    """Every check of the lesson on the run, in the lesson's order."""
    variant = lesson.variants[variant_index]
    checks = []
    for check in lesson.checks:
        found = check.evaluate(record)
        checks.append(
            CheckResult(
                check.name,
                check.KIND,
                bool(found.passed),
                check.points if found.passed else 0.0,
                check.points,
                found.message,
                None if found.t_s is None else round(float(found.t_s), 3),
            )
        )
    status = "memory" if ran_out_of_memory else RUN_STATUS.get(record.status, "error")
    message = run_message(record, status, lesson.limits.memory_mb)
    return VariantResult(variant.name, variant.hidden, status, message, round(record.end_s, 3), checks)


def not_run(lesson: Lesson, variant_index: int, status: str, message: str) -> VariantResult:
    """A variant whose run left nothing to judge: every check fails, saying why."""
    variant = lesson.variants[variant_index]
    checks = [
        CheckResult(c.name, c.KIND, False, 0.0, c.points, f"not judged: {message}") for c in lesson.checks
    ]
    return VariantResult(variant.name, variant.hidden, status, message, None, checks)
