"""Score one run of one variant: every check of the lesson on the run's record, or none if there was no run.

The gating rule: a lesson's goal checks (`goal: true`) are the task itself; every other check
(stopped, no wall contact, finished, ...) earns its points only once every goal check of the same
variant passes.  A secondary check that passes while a goal check fails is `gated`: 0 points, and the
message says why ("counts only once the robot reaches the goal"); one that fails on its own says
its own reason.  So a program that does nothing, or only prints, scores 0.

A hidden variant's result tells no more than its score, its status and which checks passed: it is named
"hidden variant N"; how its run ended is one of result.HIDDEN_RUN, chosen by how the run ended only
(never the exception's name or message, the exit code or a time: a program with 65 exceptions to choose
from could spell out a hidden wall's distance in the one it raises); and each check says one sentence for
any pass and one for any fail (its `hidden_words`, or "passed" / "did not pass (SUMMARY)"), never the
outcome's own words, which may hold what the run did.  `hidden_texts(lesson)` is every sentence a hidden
variant's result of the lesson can hold.
"""

from __future__ import annotations

import itertools

from .check import Check, Outcome
from .checks.finished import describe_error
from .lesson import Lesson
from .result import HIDDEN_RUN, CheckResult, VariantResult
from .run_record import RunRecord, seconds
from .variant import STUDENT

RUN_STATUS = {
    "finished": "graded",
    "time_limit": "graded",
    "error": "error",
    "hung": "timeout",
    "interrupted": "error",
}
GATED = "counts only once the robot reaches the goal"
# why a hidden variant's run left nothing to judge, by status: the worker's own words may quote the console
HIDDEN_NOT_RUN = {
    "timeout": HIDDEN_RUN["timeout"],
    "memory": HIDDEN_RUN["memory"],
    "output": HIDDEN_RUN["output"],
    "crashed": HIDDEN_RUN["crashed"],
    "error": HIDDEN_RUN["not_started"],
}
NOT_JUDGED = "not judged: {}"


def run_message(record: RunRecord, status: str, memory_mb: float, hidden: bool = False) -> str:
    """How the run ended, in a sentence for students (in a hidden variant one of HIDDEN_RUN, by how it ended)."""
    if hidden:
        if status == "memory":
            return HIDDEN_RUN["memory"]
        return HIDDEN_RUN.get(record.status, HIDDEN_RUN["error"])
    end = f" at {seconds(record.end_s)}"
    error = record.error or {}
    if status == "memory":
        return f"the program ran out of memory{end} (it may use {memory_mb:g} MB); line {error.get('line')}"
    if record.status == "error":
        return f"the program stopped with an error{end}: {describe_error(error)}"
    if record.status == "hung":
        return (
            f"the program got stuck{end} in a loop that never uses the robot or the clock, so it was stopped"
        )
    if record.status == "time_limit":
        return f"the program ran until the time limit of {seconds(record.end_s)}"
    return f"the program finished{end}"


def hidden_words(check: Check, passed: bool) -> str:
    """A check's sentence in a hidden variant: the same for every pass, and for every fail (so it says no
    more than pass or fail); a check kind without `hidden_words` says "passed" or its summary."""
    words = getattr(check, "hidden_words", None)
    if callable(words):
        return str(words(bool(passed)))
    return "passed" if passed else f"did not pass ({check.SUMMARY or check.KIND})"


def hidden_texts(lesson: Lesson) -> set[str]:
    """Every sentence a hidden variant's result of the lesson can hold: the run's words, each check's two
    sentences, why a secondary check earned nothing, and why nothing was judged."""
    texts = set(HIDDEN_RUN.values()) | {NOT_JUDGED.format(words) for words in HIDDEN_NOT_RUN.values()}
    for check in lesson.checks:
        texts |= {hidden_words(check, True), hidden_words(check, False)}
    goals = [check.name for check in lesson.checks if check.goal]
    for count in range(1, len(goals) + 1):
        texts |= {gated_message(list(failed)) for failed in itertools.combinations(goals, count)}
    return texts


def gated_message(failed_goals: list[str]) -> str:
    """Why a secondary check earned nothing: the goal checks that did not pass."""
    return f"{GATED} ({', '.join(failed_goals)} did not pass)"


def check_results(
    checks: list[Check], outcomes: list[Outcome], hidden: bool = False, robots: list[str] | None = None
) -> list[CheckResult]:
    """The checks' outcomes as results, with the gating rule applied (see the module docstring); with
    `robots` (the names of each check's robot, in a lesson with several), each result names its robot."""
    failed_goals = [c.name for c, o in zip(checks, outcomes, strict=True) if c.goal and not o.passed]
    results = []
    for index, (check, found) in enumerate(zip(checks, outcomes, strict=True)):
        gated = bool(failed_goals) and not check.goal and bool(found.passed)
        passed = bool(found.passed) and not gated
        if gated:
            message, t_s = gated_message(failed_goals), None
        elif hidden:
            message, t_s = hidden_words(check, passed), None
        else:
            message, t_s = found.message, None if found.t_s is None else round(float(found.t_s), 3)
        results.append(
            CheckResult(
                check.name,
                check.KIND,
                passed,
                check.points if passed else 0.0,
                check.points,
                message,
                t_s,
                goal=check.goal,
                gated=gated,
                robot=robots[index] if robots else None,
            )
        )
    return results


def score_run(
    lesson: Lesson, variant_index: int, record: RunRecord, ran_out_of_memory: bool = False
) -> VariantResult:
    """Every check of the lesson on the run (`record`: the student's robot's), each on the robot it looks
    at, in the lesson's order, gated by the goal checks."""
    variant = lesson.variants[variant_index]
    outcomes = [check.evaluate(record.for_robot(variant.robot_index(check.robot))) for check in lesson.checks]
    robots = [check.robot or STUDENT for check in lesson.checks] if lesson.several_robots else None
    checks = check_results(lesson.checks, outcomes, variant.hidden, robots)
    status = "memory" if ran_out_of_memory else RUN_STATUS.get(record.status, "error")
    message = run_message(record, status, lesson.limits.memory_mb, variant.hidden)
    sim_time_s = None if variant.hidden else round(record.end_s, 3)
    return VariantResult(variant.report_name, variant.hidden, status, message, sim_time_s, checks)


def not_run(lesson: Lesson, variant_index: int, status: str, message: str) -> VariantResult:
    """A variant whose run left nothing to judge: every check fails, saying why (in a hidden variant, only
    by its status: the message may quote what the program wrote to the console)."""
    variant = lesson.variants[variant_index]
    if variant.hidden:
        message = HIDDEN_NOT_RUN.get(status, HIDDEN_RUN["crashed"])
    several = lesson.several_robots
    checks = [
        CheckResult(
            c.name,
            c.KIND,
            False,
            0.0,
            c.points,
            NOT_JUDGED.format(message),
            goal=c.goal,
            robot=(c.robot or STUDENT) if several else None,
        )
        for c in lesson.checks
    ]
    return VariantResult(variant.report_name, variant.hidden, status, message, None, checks)
