"""`ev3sim2d grade`: grade programs (a file, a student's folder, or a class folder) in a lesson."""

from __future__ import annotations

import argparse
import signal
import sys
import tempfile
import traceback
from pathlib import Path

from ..grading.grader import default_jobs, grade
from ..grading.lesson import list_shipped_lessons, load_lesson
from ..grading.report import (
    details,
    score_text,
    table,
    write_classroom,
    write_csv,
    write_junit,
)
from ..grading.safe_text import one_line
from ..grading.submission import DEFAULT_ENTRY, find_submissions
from ..grading.worker import CheckError
from ..results.output_files import read_limited, write_file
from ..simulator.scratch import remove_tree
from ..world.source_error import WorldFileError
from .doctor import grading_isolation, this_computer
from .exit_codes import EXIT_INTERNAL, EXIT_INTERRUPTED, EXIT_OK, EXIT_PROGRAM_ERROR, EXIT_USAGE, fail

NAME = "grade"
MAX_TRACE_BYTES = 512 * 2**20  # a failed run's trace kept for --videos
HELP = "grade programs in a lesson: one file, a student's folder, or a folder of a whole class"
EPILOG = f"""exit status:
  {EXIT_OK}    every program scored at least --pass-percent (default: full marks)
  {EXIT_PROGRAM_ERROR}    some program scored less (in a class: any one of them), or could not be started
  {EXIT_USAGE}    usage error: a wrong option, a missing lesson or folder, a broken lesson or check
  {EXIT_INTERNAL}    internal error: a bug in ev3sim2d (the traceback is printed; please report it)
  {130}  interrupted (Ctrl+C, or ended by a signal); run it again with --json FILE --resume to go on
  141  the output's reader went away (e.g. `ev3sim2d grade ... | head`)"""


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.epilog = EPILOG
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    lessons = ", ".join(list_shipped_lessons()) or "none"
    parser.add_argument(
        "lesson",
        metavar="LESSON",
        help=f"a shipped lesson's id ({lessons}), a lesson's id in --lessons DIR, or a lesson folder written as "
        "a path (./my-lesson): a bare name is never taken from the folder you grade in",
    )
    parser.add_argument(
        "programs",
        nargs="+",
        metavar="PROG",
        help="a program file, a student's folder (with main.py), or a folder with one program or folder per student",
    )
    parser.add_argument(
        "--jobs",
        type=int,
        default=None,
        metavar="N",
        help=f"grade N runs at a time (default: {default_jobs()} here for a lesson of one robot; a core for each "
        "process of a run, the simulator and each robot's brick, where they can spin as they wait)",
    )
    parser.add_argument(
        "--json",
        metavar="FILE",
        help="write the results as JSON, rewritten as each submission finishes (with --resume, take the results "
        "of unchanged submissions this grader already wrote there)",
    )
    parser.add_argument(
        "--junit", metavar="FILE", help="write JUnit XML (one test per variant and check), for CI"
    )
    parser.add_argument(
        "--csv",
        metavar="FILE",
        help="write one CSV row per submission, for the class list (UTF-8 with a BOM: Excel opens it as it is)",
    )
    parser.add_argument(
        "--classroom",
        metavar="FILE",
        help="a single program: append GitHub Classroom's autograding result (result=BASE64) to FILE, "
        'in a workflow "$GITHUB_OUTPUT": points out of the lesson\'s max (docs/github-classroom.md)',
    )
    parser.add_argument(
        "--videos",
        metavar="DIR",
        help="keep a video (or the trace and a picture) of each failed visible variant",
    )
    parser.add_argument(
        "--hidden-videos",
        action="store_true",
        help="with --videos: hidden variants' videos too, named by variant (for the teacher's eyes only: "
        "they show the hidden worlds)",
    )
    parser.add_argument(
        "--lessons",
        metavar="DIR",
        help="a folder of your own lessons, where LESSON is looked up by id before the shipped ones",
    )
    parser.add_argument(
        "--hidden",
        metavar="DIR",
        help="the lesson's hidden variants from a teacher's private copy: a folder holding hidden.yaml and "
        "its worlds, or one holding LESSON_ID/hidden.yaml (default: the lesson's own hidden/ folder, if any)",
    )
    parser.add_argument(
        "--entry",
        default=DEFAULT_ENTRY,
        metavar="NAME",
        help=f"the file to run in a student's folder (default: {DEFAULT_ENTRY})",
    )
    parser.add_argument(
        "--resume",
        action="store_true",
        help="with --json FILE: go on where an earlier run stopped; a result is taken again only if this "
        "grader signed it (a results file someone else wrote or changed is graded again)",
    )
    parser.add_argument("--details", action="store_true", help="show every check of every submission")
    parser.add_argument(
        "--pass-percent",
        type=float,
        default=100.0,
        metavar="P",
        help="exit with status 1 when a program (in a class: any one) scores below P%% (default: 100)",
    )
    parser.add_argument("--quiet", action="store_true", help="no progress lines while grading")
    parser.add_argument(
        "--require-sandbox",
        action="store_true",
        help="refuse to grade where programs would not get file confinement, network confinement and "
        "clean-up of what they start (Windows and macOS: docs/platforms.md)",
    )


class EndedBySignal(KeyboardInterrupt):
    """SIGTERM or SIGHUP (a `timeout`, a cancelled CI job, a closed terminal): ended as Ctrl+C ends it."""

    def __init__(self, signal_number: int) -> None:
        super().__init__(f"signal {signal_number}")
        self.signal_number = signal_number


def _end_on_signals() -> dict:
    """SIGTERM and SIGHUP end grading as Ctrl+C does: every process it started is ended, and what was
    done is written (the signals' earlier handlers, to put back)."""

    def ended(number, frame) -> None:
        raise EndedBySignal(number)

    earlier = {}
    for name in ("SIGTERM", "SIGHUP"):
        number = getattr(signal, name, None)
        if number is not None:
            try:
                earlier[number] = signal.signal(number, ended)
            except (ValueError, OSError):  # (not the main thread: a caller that handles it)
                pass
    return earlier


def main(args) -> int:
    earlier = _end_on_signals()
    try:
        return _grade(args)
    except KeyboardInterrupt as interrupt:
        print("ev3sim2d: grading interrupted", file=sys.stderr)
        return _interrupted_status(interrupt)
    except (BrokenPipeError, SystemExit):
        raise  # the command line's own (cli.py)
    except Exception:  # noqa: BLE001 - our bug: said loudly, with its own exit status
        traceback.print_exc()
        print("ev3sim2d: internal error: this is a bug in ev3sim2d; please report it", file=sys.stderr)
        return EXIT_INTERNAL
    finally:
        for number, handler in earlier.items():
            signal.signal(number, handler)


def _grade(args) -> int:
    if args.jobs is not None and args.jobs < 1:
        return fail("--jobs must be at least 1")
    if args.hidden_videos and not args.videos:
        return fail("--hidden-videos needs --videos DIR")
    try:
        lesson = load_lesson(args.lesson, hidden=args.hidden, lessons=args.lessons)
    except WorldFileError as err:
        return fail(str(err))
    if not lesson.hidden_variants() and not args.quiet:
        print(
            f"ev3sim2d: {lesson.id} has no hidden variants here: grading its visible variants only "
            "(a teacher adds the hidden ones with --hidden DIR)",
            file=sys.stderr,
        )
    isolation = grading_isolation(this_computer())
    if isolation["missing"]:
        what = ", ".join(f"no {name}" for name in isolation["missing"])
        if args.require_sandbox:
            return fail(
                f"--require-sandbox: a class's programs would get {what} on this computer; grade on Linux "
                "or in CI (docs/platforms.md)"
            )
        if not args.quiet:
            print(
                f"ev3sim2d: on this computer a class's programs get {what}: fine for your own or trusted "
                "programs; for a class you do not trust, grade on Linux or in CI (docs/platforms.md)",
                file=sys.stderr,
            )
    submissions = find_submissions(args.programs, args.entry)
    if not submissions:
        return fail("no programs to grade")
    if args.classroom and len(submissions) != 1:
        return fail(f"--classroom grades a single program; {len(submissions)} were found", EXIT_USAGE)

    total = len(submissions)
    finished = {"n": 0}

    def progress(result) -> None:
        finished["n"] += 1
        if not args.quiet:
            print(
                f"[{finished['n']:>{len(str(total))}}/{total}] {one_line(result.submission)}: {score_text(result)} ({result.status})",
                file=sys.stderr,
            )

    on_failed_run = None
    failed_runs: list[tuple[str, str, Path]] = []
    holding = Path(tempfile.mkdtemp(prefix="ev3sim2d-videos-")) if args.videos else None
    if args.videos:

        def on_failed_run(submission, variant_index, trace_path) -> None:
            # videos are made once grading is over: no rendering threads while workers are forked
            variant = lesson.variants[variant_index]
            if variant.hidden and not args.hidden_videos:
                return  # a video would show the hidden world
            kept = holding / f"{len(failed_runs)}.npz"
            write_file(kept, read_limited(trace_path, MAX_TRACE_BYTES))  # (never through a planted link)
            failed_runs.append((submission.name, variant.name, kept))

    try:
        grading = grade(
            lesson,
            submissions,
            args.jobs,
            args.json,
            args.resume,
            progress,
            on_failed_run,
            isolation=isolation,
        )
        if args.videos:
            _keep_failed_runs(Path(args.videos), failed_runs, args.quiet)
    except CheckError as err:  # a bug in a check, most likely in the lesson's check_*.py
        return fail(str(err))
    except KeyboardInterrupt as interrupt:
        done = getattr(interrupt, "grading", None)
        if done is not None:  # the reports of what was done, so that nothing done is lost
            _write_reports(args, done)
        kept = f"; the submissions graded so far are in {args.json}" if args.json else ""
        print(f"ev3sim2d: grading interrupted{kept}; run it again with --resume to go on", file=sys.stderr)
        return _interrupted_status(interrupt)
    finally:
        if holding is not None:
            remove_tree(holding)
    if not _write_reports(args, grading):
        return EXIT_USAGE

    if len(grading.results) == 1 or args.details:
        for result in grading.results:
            print(details(result))
    if len(grading.results) > 1:
        print(table(grading))
    if grading.reused and not args.quiet:
        print(
            f"ev3sim2d: {grading.reused} result(s) taken from {args.json} (unchanged submissions)",
            file=sys.stderr,
        )
    below = [r for r in grading.results if _percent(r) + 1e-9 < args.pass_percent]
    if below and len(grading.results) > 1 and not args.quiet:
        print(
            f"ev3sim2d: {len(below)} of {len(grading.results)} submission(s) scored below {args.pass_percent:g}%",
            file=sys.stderr,
        )
    return EXIT_PROGRAM_ERROR if below else EXIT_OK


def _write_reports(args, grading) -> bool:
    """JUnit, CSV and the classroom line (the grader wrote --json as it went, each result signed);
    False, said on stderr, when one could not be written."""
    try:
        if args.junit:
            write_junit(args.junit, grading)
        if args.csv:
            write_csv(args.csv, grading)
        if args.classroom:
            write_classroom(args.classroom, grading, args.pass_percent)
    except OSError as err:
        fail(f"could not write the results: {err}")
        return False
    return True


def _interrupted_status(interrupt: BaseException) -> int:
    """130 for Ctrl+C, as a shell shows it; 128 + N for signal N (143 for SIGTERM)."""
    number = getattr(interrupt, "signal_number", None)
    return 128 + number if number else EXIT_INTERRUPTED


def _percent(result) -> float:
    return 100.0 * result.score / result.max_score if result.max_score else 0.0


def _keep_failed_runs(folder: Path, failed_runs: list[tuple[str, str, Path]], quiet: bool) -> None:
    from ..grading.videos import keep_failed_run, video_writer

    if not failed_runs:
        return
    if not quiet:
        what = "videos" if video_writer() is not None else "traces and pictures (no video writer here)"
        print(f"ev3sim2d: writing {what} of {len(failed_runs)} failed run(s) to {folder}", file=sys.stderr)
    for submission, variant, trace_path in failed_runs:
        keep_failed_run(folder, submission, variant, trace_path)
