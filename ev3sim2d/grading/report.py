"""Grading results for people and machines: a terminal table, per-check details, JSON, JUnit XML and CSV.

Hidden variants appear as "hidden variant N" with their score and what went wrong in words (the
results hold nothing more of them, see scoring.py); a secondary check that earned nothing because the
goal was not met is marked `----`, and skipped in JUnit.
"""

from __future__ import annotations

import csv
import os
import xml.etree.ElementTree as ET
from pathlib import Path

from .grader import Grading, write_results
from .lesson import Lesson
from .result import SubmissionResult, VariantResult
from .safe_text import one_line, printable, spreadsheet_cell

FAILURE_WIDTH = 70


def _points(value: float) -> str:
    return f"{value:g}" if float(value).is_integer() else f"{value:.1f}"


def score_text(result: SubmissionResult) -> str:
    return f"{_points(result.score)}/{_points(result.max_score)}"


def table(grading: Grading) -> str:
    """One line per submission: score, status, each variant's score, and the first thing that went wrong."""
    lesson = grading.lesson
    labels = [v.report_name for v in lesson.variants]
    header = ["submission", "score", "status", *labels, "first problem"]
    rows = []
    for result in grading.results:
        by_name = {v.name: v for v in result.variants}
        cells = [_points(by_name[name].score) if name in by_name else "-" for name in labels]
        failure = result.first_failure()
        if len(failure) > FAILURE_WIDTH:
            failure = failure[: FAILURE_WIDTH - 3] + "..."
        rows.append(
            [one_line(result.submission), score_text(result), result.status, *cells, one_line(failure)]
        )
    widths = [max(len(str(row[i])) for row in [header, *rows]) for i in range(len(header))]
    hidden = len(lesson.hidden_variants())
    lines = [
        f"{lesson.id}: {lesson.title} ({len(lesson.variants)} variants, {hidden} of them hidden, "
        f"{_points(lesson.max_score)} points)"
    ]
    for row in [header, *rows]:
        lines.append(
            "  ".join(str(cell).ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
        )
    full = sum(1 for r in grading.results if r.full_marks)
    lines.append(f"{len(grading.results)} submission(s), {full} with full marks")
    return "\n".join(lines)


def hidden_summary(variant: VariantResult) -> str:
    """ "passed", or "failed — the robot touched a wall": all a report says of a hidden variant's run."""
    if variant.passed:
        return "passed"
    failed = variant.failed_checks()
    reason = variant.message if variant.status != "graded" or not failed else failed[0].message
    return f"failed — {reason}"


def variant_details(variant: VariantResult) -> list[str]:
    score = f"{_points(variant.score)}/{_points(variant.max_score)}"
    if variant.hidden:
        lines = [f"  {variant.name}: {score}, {hidden_summary(variant)}"]
    else:
        lines = [f"  {variant.name}: {score}, {variant.message}"]
    for check in variant.checks:
        mark = "PASS" if check.passed else "----" if check.gated else "FAIL"
        goal = ", goal" if check.goal else ""
        robot = f", robot: {check.robot}" if check.robot else ""
        points = f"{_points(check.points)}/{_points(check.max_points)}{goal}{robot}"
        lines.append(f"    {mark} {check.name} ({points}): {check.message}")
    return lines


def details(result: SubmissionResult) -> str:
    """Every variant and check of one submission, as a student reads it."""
    lines = [f"{result.submission}: {score_text(result)} ({result.status})"]
    if result.problem:
        lines.append(f"  {result.problem}")
    for variant in result.variants:
        lines += variant_details(variant)
    return printable("\n".join(lines))


def write_json(path: str | Path, grading: Grading) -> None:
    write_results(Path(path), grading.lesson, grading.results)


def junit_tree(lesson: Lesson, results: list[SubmissionResult]) -> ET.ElementTree:
    """A <testsuites> with one <testsuite> per submission and one <testcase> per variant and check."""
    suites = ET.Element("testsuites", name=f"ev3sim2d {lesson.id}")
    total_tests = total_failures = total_errors = total_skipped = 0
    for result in results:
        suite = ET.SubElement(suites, "testsuite", name=result.submission)
        tests = failures = errors = skipped = 0
        if result.problem:
            case = ET.SubElement(
                suite, "testcase", classname=f"{lesson.id}.{result.submission}", name="program"
            )
            ET.SubElement(case, "error", message=result.problem, type="missing")
            tests, errors = 1, 1
        for variant in result.variants:
            for check in variant.checks:
                tests += 1
                case = ET.SubElement(
                    suite,
                    "testcase",
                    classname=f"{lesson.id}.{variant.name}",
                    name=check.name,
                )
                case.set("points", _points(check.points))
                case.set("max_points", _points(check.max_points))
                if check.passed:
                    ET.SubElement(case, "system-out").text = check.message
                elif check.gated:
                    skipped += 1
                    ET.SubElement(case, "skipped", message=check.message)
                elif variant.status in ("graded", "error"):
                    failures += 1
                    ET.SubElement(
                        case, "failure", message=check.message, type=check.kind
                    ).text = check.message
                else:
                    errors += 1
                    ET.SubElement(
                        case, "error", message=check.message, type=variant.status
                    ).text = variant.message
        suite.set("tests", str(tests))
        suite.set("failures", str(failures))
        suite.set("errors", str(errors))
        suite.set("skipped", str(skipped))
        suite.set("score", _points(result.score))
        suite.set("max_score", _points(result.max_score))
        total_tests, total_failures, total_errors, total_skipped = (
            total_tests + tests,
            total_failures + failures,
            total_errors + errors,
            total_skipped + skipped,
        )
    suites.set("tests", str(total_tests))
    suites.set("failures", str(total_failures))
    suites.set("errors", str(total_errors))
    suites.set("skipped", str(total_skipped))
    for element in suites.iter():  # a program's words, made fit for XML
        if element.text:
            element.text = printable(element.text)
        for name, value in element.attrib.items():
            element.set(name, printable(value))
    ET.indent(suites)
    return ET.ElementTree(suites)


def write_junit(path: str | Path, grading: Grading) -> None:
    _replace(
        Path(path),
        lambda p: junit_tree(grading.lesson, grading.results).write(
            p, encoding="utf-8", xml_declaration=True
        ),
    )


def write_csv(path: str | Path, grading: Grading) -> None:
    """One row per submission: for the class list."""
    lesson = grading.lesson

    def write(part: Path) -> None:
        with open(part, "w", newline="", encoding="utf-8") as f:
            out = csv.writer(f)
            out.writerow(
                [
                    "submission",
                    "status",
                    "score",
                    "max_score",
                    "percent",
                    *[v.report_name for v in lesson.variants],
                    "first_problem",
                ]
            )
            for result in grading.results:
                by_name = {v.name: v for v in result.variants}
                percent = 100.0 * result.score / result.max_score if result.max_score else 0.0
                out.writerow(
                    [
                        spreadsheet_cell(result.submission),
                        result.status,
                        _points(result.score),
                        _points(result.max_score),
                        f"{percent:.0f}",
                        *[
                            _points(by_name[v.report_name].score) if v.report_name in by_name else ""
                            for v in lesson.variants
                        ],
                        spreadsheet_cell(result.first_failure()),
                    ]
                )

    _replace(Path(path), write)


def _replace(path: Path, write) -> None:
    """Write through a temporary file, so a reader never sees half of it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    part = path.with_name(path.name + ".part")
    write(part)
    os.replace(part, path)
