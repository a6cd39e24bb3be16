"""Grading results for people and machines: a terminal table, per-check details, JSON, JUnit XML, CSV, and
GitHub Classroom's autograding result.

JUnit XML uses only the attributes of the JUnit XSD that CI systems read (`JUNIT_ATTRIBUTES`); points and
details are in each test case's `<system-out>`.  The CSV is UTF-8 with a byte order mark, so that Excel
opens it with its accents and names right.

Hidden variants appear as "hidden variant N" with their score, status and which checks passed, in fixed
words (the results hold nothing more of them, see scoring.py); a secondary check that earned nothing because
the goal was not met is marked `----`, and skipped in JUnit.  No report holds a wall-clock time a program
could stretch: JUnit's `time` is the simulated seconds of the visible variants' runs, and its `timestamp`
the moment grading began.

Text a program chose (a submission's name, an error message, a traceback) is shown through safe_text.py:
control characters and BiDi overrides escaped for a terminal, characters XML forbids, no spreadsheet formulas.
"""

from __future__ import annotations

import base64
import csv
import json
import socket
import time
import xml.etree.ElementTree as ET
from pathlib import Path

from ..results.output_files import append_text, writing
from .grader import Grading, write_results
from .lesson import Lesson
from .result import SubmissionResult, VariantResult
from .safe_text import one_line, printable, spreadsheet_cell

FAILURE_WIDTH = 70
CSV_ENCODING = "utf-8-sig"  # with a BOM: Excel reads the file as UTF-8 only when it starts with one
JUNIT_ATTRIBUTES = {  # all the attributes written: those of the JUnit XSD (Jenkins' junit-10.xsd)
    "testsuites": ("name", "tests", "failures", "errors", "skipped", "time"),
    "testsuite": ("name", "tests", "failures", "errors", "skipped", "time", "timestamp", "hostname", "id"),
    "testcase": ("name", "classname", "time"),
    "failure": ("message", "type"),
    "error": ("message", "type"),
    "skipped": ("message",),
}


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
        lines += [f"  {line}" for line in result.problem.splitlines()]
    for variant in result.variants:
        lines += variant_details(variant)
    return printable("\n".join(lines))


def write_json(path: str | Path, grading: Grading) -> None:
    write_results(Path(path), grading.lesson, grading.results, grading.isolation)


def _check_text(variant: VariantResult, check) -> str:
    """A test case's <system-out>: its points and what the check found."""
    points = f"{_points(check.points)}/{_points(check.max_points)} points"
    goal = ", a goal check" if check.goal else ""
    robot = f", robot: {check.robot}" if check.robot else ""
    run = hidden_summary(variant) if variant.hidden else variant.message
    return f"{points}{goal}{robot}\n{check.message}\nthe run: {run}"


def junit_tree(
    lesson: Lesson, results: list[SubmissionResult], timestamp: float | None = None
) -> ET.ElementTree:
    """A <testsuites> with one <testsuite> per submission and one <testcase> per variant and check; `time`
    is the simulated seconds of the visible variants' runs, `timestamp` (default: now) when grading began."""
    suites = ET.Element("testsuites", name=f"ev3sim2d {lesson.id}")
    stamp = time.strftime("%Y-%m-%dT%H:%M:%S", time.localtime(timestamp))
    host = socket.gethostname() or "localhost"
    total_tests = total_failures = total_errors = total_skipped = 0
    for number, result in enumerate(results):
        suite = ET.SubElement(
            suites, "testsuite", name=result.submission, id=str(number), timestamp=stamp, hostname=host
        )
        tests = failures = errors = skipped = 0
        if result.problem:
            case = ET.SubElement(
                suite, "testcase", classname=f"{lesson.id}.{result.submission}", name="program"
            )
            first = result.problem.splitlines()[0]
            ET.SubElement(case, "error", message=first, type=result.status).text = result.problem
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
                if check.passed:
                    pass
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
                    ET.SubElement(case, "error", message=check.message, type=variant.status).text = (
                        variant.message if not variant.hidden else hidden_summary(variant)
                    )
                ET.SubElement(case, "system-out").text = _check_text(variant, check)
        for name, value in (
            ("tests", tests),
            ("failures", failures),
            ("errors", errors),
            ("skipped", skipped),
        ):
            suite.set(name, str(value))
        ET.SubElement(
            suite, "system-out"
        ).text = f"{result.submission}: {score_text(result)} points ({result.status})"
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
    simulated = sum(v.sim_time_s or 0.0 for r in results for v in r.variants if not v.hidden)
    suites.set("time", f"{simulated:.3f}")
    for element in suites.iter():  # a program's words, made fit for XML
        if element.text:
            element.text = printable(element.text)
        for name, value in element.attrib.items():
            element.set(name, printable(value))
    ET.indent(suites)
    return ET.ElementTree(suites)


def write_junit(path: str | Path, grading: Grading) -> None:
    began = time.time() - grading.wall_s  # (the end would tell how long the programs took)
    _replace(
        Path(path),
        lambda p: junit_tree(grading.lesson, grading.results, began).write(
            p, encoding="utf-8", xml_declaration=True
        ),
    )


def write_csv(path: str | Path, grading: Grading) -> None:
    """One row per submission: for the class list."""
    lesson = grading.lesson

    def write(part: Path) -> None:
        with open(part, "w", newline="", encoding=CSV_ENCODING) as f:
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


def classroom_result(grading: Grading, pass_percent: float = 100.0) -> dict:
    """GitHub Classroom's autograding result of one submission, as classroom-resources/autograding-grading-
    reporter reads it (version 1, as autograding-command-grader writes it): a test per variant and check
    with the points it earned, so Classroom's points are the lesson's score out of its max, not all or
    nothing.  Hidden variants by number only, with their checks' messages (which hold no numbers)."""
    [result] = grading.results
    tests = []
    if result.problem:
        tests.append(_classroom_test("program", "error", 0, result.problem))
    for variant in result.variants:
        for check in variant.checks:
            status = "pass" if check.passed else "fail" if variant.status in ("graded", "error") else "error"
            tests.append(
                _classroom_test(f"{variant.name}: {check.name}", status, check.points, check.message)
            )
    percent = 100.0 * result.score / result.max_score if result.max_score else 0.0
    status = "error" if result.problem else "pass" if percent + 1e-9 >= pass_percent else "fail"
    return {"version": 1, "status": status, "max_score": _number(result.max_score), "tests": tests}


def _classroom_test(name: str, status: str, score: float, message: str) -> dict:
    return {
        "name": printable(name),
        "status": status,
        "score": _number(score),
        "message": printable(message),
        "test_code": "",
        "filename": "",
        "line_no": 0,
        "duration": 0,
    }


def _number(value: float) -> float | int:
    return int(value) if float(value).is_integer() else round(float(value), 3)


def write_classroom(path: str | Path, grading: Grading, pass_percent: float = 100.0) -> None:
    """Append `result=<base64 JSON>` to path: in a workflow "$GITHUB_OUTPUT", which makes it the step's
    output `result`, for the autograding reporter (docs/github-classroom.md)."""
    encoded = base64.b64encode(json.dumps(classroom_result(grading, pass_percent)).encode()).decode()
    append_text(path, f"result={encoded}\n")


def _replace(path: Path, write) -> None:
    """Write through a new temporary file, renamed over path: a reader never sees half of it, and a
    link planted at either name is never written through (output_files.py)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with writing(path) as temporary:
        write(temporary)
