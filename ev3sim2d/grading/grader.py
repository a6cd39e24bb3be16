"""Grade submissions in a lesson: workers in parallel, results saved as each submission is complete.

Each submission runs once per variant, each run in its own worker process
(`worker.py`), at most `jobs` at a time; the worker scores its run with the
lesson's checks.  A run that leaves no result (killed at its limit, crashed)
gets every check failed with the reason.  When all of a submission's variants are in, its
result is complete: it is handed to `on_result` and the results file is
rewritten (atomically), so an interrupted class run loses nothing that was
done.  Run again with the same results file and `resume`, and unchanged submissions
are not graded again (their key, a hash of the lesson and the submission's files,
is the same, and so would be their score) if this grader signed their results
(grader_key.py): a results file someone else wrote is never taken as grading.
"""

from __future__ import annotations

import gc
import json
import os
import secrets
import select
import shutil
import socket
import tempfile
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from ..protocol.stream import can_spin
from ..results.output_files import read_limited, write_file
from ..simulator.bricks import become_subreaper, compile_brick_code, kill_orphans, portable
from ..simulator.scratch import remove_tree
from .grader_key import grader_key, signature, signed_by_this_grader
from .lesson import HIDDEN_DIR, Lesson, find_hidden
from .result import SubmissionResult, VariantResult
from .scoring import not_run
from .submission import Submission
from .variant import Variant
from .worker import Job, JobOutcome, RunningJob, collect, start_job

POLL_S = 0.01
RESULTS_FORMAT = "ev3sim2d-grades-1"
MAX_RESULTS_BYTES = 64 * 2**20  # a results file read back to resume (a class of thousands)


@dataclass
class Grading:
    """The results of grading, in the order the submissions were given."""

    lesson: Lesson
    results: list[SubmissionResult]
    reused: int = 0  # results taken over from an earlier run
    wall_s: float = 0.0
    isolation: dict | None = None  # what the programs were kept from on this computer (doctor.py)


class GradingInterrupted(KeyboardInterrupt):
    """Grading stopped early (Ctrl+C, or a signal that ends it: signal_number); `grading` holds the
    submissions that were done, so that their reports can still be written."""

    def __init__(self, grading: Grading, signal_number: int | None = None) -> None:
        super().__init__("grading was interrupted")
        self.grading = grading
        self.signal_number = signal_number


@dataclass
class _Pending:
    submission: Submission
    key: str
    variants: dict[int, VariantResult] = field(default_factory=dict)
    unstartable: dict[int, str] = field(default_factory=dict)  # variant -> why its brick could not start it

    def result(self, lesson: Lesson) -> SubmissionResult:
        """The submission's result once every variant is in; a program no brick could even compile (a
        syntax error) is one problem, said once with its line and caret, not once per variant."""
        reasons = set(self.unstartable.values())
        if len(self.unstartable) == len(lesson.variants) and len(reasons) == 1:
            return SubmissionResult(
                self.submission.name,
                self.key,
                problem=reasons.pop(),
                max_points=lesson.max_score,
                problem_status="error",
            )
        return SubmissionResult(
            self.submission.name, self.key, [self.variants[v] for v in range(len(lesson.variants))]
        )


class CoreShare:
    """Which core each run gets, when runs must share the cores.

    A run is two processes that take turns (the simulator steps the world while the brick computes, and
    each waits for the other's next message).  With a core for each of them they spin and never sleep;
    with fewer, a sleeping process is woken by the other from another core, which costs about 100 us of
    CPU on a virtual machine, against about 17 us for a hand-over on one core.  So when the jobs have
    fewer than two cores each, each run keeps to one core, and the cores are shared out evenly."""

    def __init__(self, jobs: int) -> None:
        allowed = allowed_cores()
        self.cores = allowed if jobs * 2 > len(allowed) else []

    def least_used(self, taken: list[int | None]) -> int | None:
        """The core with the fewest runs on it now (None: runs are not pinned)."""
        if not self.cores:
            return None
        return min(self.cores, key=lambda core: (taken.count(core), core))


def _wait_for_one(pids: list[int], timeout_s: float) -> None:
    """Sleep until one of these processes ends, or timeout_s: a free slot is filled at once."""
    fds: list[int] = []
    try:
        for pid in pids:
            fds.append(os.pidfd_open(pid))
        select.select(fds, [], [], timeout_s)
    except (AttributeError, OSError):  # no pidfds (not Linux >= 5.3): look again after a while
        time.sleep(timeout_s)
    finally:
        for fd in fds:
            os.close(fd)


def _start_zygote():
    """The class run's brick zygote (simulator/zygote.py), or None where there can be none: each brick is
    then started afresh."""
    if portable() or not hasattr(socket, "send_fds") or not hasattr(socket, "SOCK_SEQPACKET"):
        return None
    from ..simulator.zygote import BrickZygote

    try:
        return BrickZygote()
    except OSError:
        return None


def allowed_cores() -> list[int]:
    """The cores this process may run on (all of them where the system does not say)."""
    try:
        return sorted(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return list(range(os.cpu_count() or 1))


def default_jobs(lesson: Lesson | None = None) -> int:
    """Runs at a time, unless the teacher says: where a run's processes can spin as they wait for each
    other (protocol/stream.can_spin), as many runs as give each process of a run a core of its own (the
    simulator, and the brick of each robot of the lesson's runs: one robot without a lesson), so that
    every run spins, and one alone on the machine places them (simulator/cores.py); elsewhere, where each
    waits asleep, one run a core.  On 2 cores, one run at a time graded a class of 30 on the two-robot
    convoy lesson in 82-84 s, against 118-122 s two at a time (each run then on one core); 30 line
    followers in 15-18 s either way, with a quarter less CPU (benchmarks/grade.py --compare-jobs 2)."""
    cores = len(allowed_cores())
    if not can_spin():
        return max(1, cores)
    robots = 1 + max((len(variant.others) for variant in lesson.variants), default=0) if lesson else 1
    return max(1, cores // (1 + robots))


def can_fork() -> bool:
    """Whether workers may be forked from the grader: where Python itself forks by default (not where
    a forked child of a process that loaded the system's libraries may crash, as on macOS, whose
    default is spawn), and not on the portable path (EV3SIM2D_PORTABLE=1), which spawns as Windows must."""
    import multiprocessing

    return hasattr(os, "fork") and not portable() and multiprocessing.get_all_start_methods()[0] != "spawn"


def variant_result_of(lesson: Lesson, variant_index: int, outcome: JobOutcome) -> VariantResult:
    """The worker's score for the variant, or every check failed with the reason the run left none."""
    if outcome.variant is not None:
        return outcome.variant
    return not_run(lesson, variant_index, outcome.outcome, outcome.message)


def load_results(path: Path, lesson: Lesson, key: bytes | None) -> dict[str, SubmissionResult]:
    """Results this grader signed in an earlier run of the same lesson, by key (nothing if the file is
    missing, another lesson's, or not this grader's; a result whose signature fails is left out)."""
    if key is None:
        return {}
    try:
        data = json.loads(read_limited(path, MAX_RESULTS_BYTES))
    except (OSError, ValueError):
        return {}
    if not isinstance(data, dict) or data.get("format") != RESULTS_FORMAT or data.get("lesson") != lesson.id:
        return {}
    found = {}
    for item in data.get("submissions", []):
        if not isinstance(item, dict) or not signed_by_this_grader(key, lesson.id, item):
            continue
        try:
            result = SubmissionResult.from_dict(item)
        except (KeyError, TypeError):
            continue
        if result.key and result.status != "crashed":  # a crash may have been the machine's: run it again
            found[result.key] = result
    return found


def results_document(
    lesson: Lesson, results: list[SubmissionResult], isolation: dict | None = None, key: bytes | None = None
) -> dict:
    """The JSON results file: the lesson, what the programs were kept from on this computer, and per
    submission its score, status, variants and checks, signed with the grader's key when given."""
    document = {
        "format": RESULTS_FORMAT,
        "lesson": lesson.id,
        "title": lesson.title,
        "max_score": lesson.max_score,
        "variants": [_variant_entry(v) for v in lesson.variants],
    }
    if isolation is not None:
        document["isolation"] = isolation
    document["submissions"] = [r.to_dict() for r in results]
    if key is not None:
        for item in document["submissions"]:
            item["signature"] = signature(key, lesson.id, item)
    return document


def _variant_entry(variant: Variant) -> dict:
    """A variant in the results file: a hidden one only by its number, never its name or world."""
    if variant.hidden:
        return {"name": variant.report_name, "hidden": True}
    return {"name": variant.name, "hidden": False, "world": variant.world().name}


def write_results(
    path: Path,
    lesson: Lesson,
    results: list[SubmissionResult],
    isolation: dict | None = None,
    key: bytes | None = None,
) -> None:
    """Write the results file atomically (a reader never sees half a file), never through a name
    someone planted in the folder (output_files.py)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    write_file(path, json.dumps(results_document(lesson, results, isolation, key), indent=2) + "\n")


def _folder_for_spawned_workers(lesson: Lesson, workdir: Path) -> str:
    """The lesson folder a spawned worker reads again: the lesson's own, unless its hidden variants come
    from elsewhere (a teacher's private copy), then a copy of it with those as its own hidden/ folder."""
    if lesson.hidden_file is None or lesson.hidden_file == find_hidden(lesson.folder):
        return str(lesson.folder)
    copy = workdir / "lesson" / lesson.id
    shutil.copytree(lesson.folder, copy, ignore=shutil.ignore_patterns(HIDDEN_DIR, "__pycache__"))
    shutil.copytree(lesson.hidden_file.parent, copy / HIDDEN_DIR)
    return str(copy)


def _cannot_start(submission: Submission) -> str | None:
    """Why the submission's program cannot be started in any variant (missing, a folder, over the size
    limit), or None.  The file is only looked at here: it is compiled only inside its bricks."""
    from ..simulator.program import Program, ProgramError

    try:
        Program(submission.entry)
    except ProgramError as err:
        return str(err)
    return None


def grade(
    lesson: Lesson,
    submissions: list[Submission],
    jobs: int | None = None,
    results_path: str | Path | None = None,
    resume: bool = False,
    on_result: Callable[[SubmissionResult], None] | None = None,
    on_failed_run: Callable[[Submission, int, Path], None] | None = None,
    use_fork: bool | None = None,
    isolation: dict | None = None,
) -> Grading:
    """Grade every submission in every variant of the lesson; see the module docstring.

    `on_failed_run(submission, variant_index, trace_path)` is called (before the trace is deleted) for each
    run that did not pass every check, e.g. to keep its trace or render a video.  `isolation` (what the
    programs are kept from on this computer) goes into the results file as it is.  resume: take the
    results this grader signed in `results_path` for unchanged submissions, instead of grading them.
    """
    started = time.monotonic()
    become_subreaper()  # a brick's orphans come back here, and are ended (kill_orphans)
    jobs = max(1, jobs or default_jobs(lesson))
    use_fork = can_fork() if use_fork is None else use_fork
    results_file = Path(results_path) if results_path else None
    digest = lesson.digest()
    signing_key = grader_key() if results_file else None
    earlier = load_results(results_file, lesson, signing_key) if results_file and resume else {}
    for variant in lesson.variants:
        variant.world()  # read before forking, so every worker has it
    compile_brick_code()  # once here, not in every worker
    done: dict[int, SubmissionResult] = {}
    pending: dict[int, _Pending] = {}
    queue: list[Job] = []
    workdir = Path(tempfile.mkdtemp(prefix="ev3sim2d-grade-"))
    lesson_folder = str(lesson.folder) if use_fork else _folder_for_spawned_workers(lesson, workdir)
    reused = 0

    def finish(index: int, result: SubmissionResult) -> None:
        done[index] = result
        if results_file is not None:
            write_results(results_file, lesson, [done[i] for i in sorted(done)], isolation, signing_key)
        if on_result is not None:
            on_result(result)

    for index, submission in enumerate(submissions):
        key = submission.key(digest)
        if key in earlier:
            result = earlier[key]
            result.submission = submission.name
            done[index] = result
            reused += 1
            continue
        if submission.entry is None:
            pending_result = SubmissionResult(
                submission.name, key, problem=submission.problem, max_points=lesson.max_score
            )
            done[index] = pending_result
            continue
        unstartable = _cannot_start(submission)
        if unstartable is not None:  # a missing or oversized file: said once, not once per variant
            done[index] = SubmissionResult(
                submission.name, key, problem=unstartable, max_points=lesson.max_score, problem_status="error"
            )
            continue
        pending[index] = _Pending(submission, key)
        for v, variant in enumerate(lesson.variants):
            queue.append(
                Job(
                    submission=index,
                    variant=v,
                    entry=str(submission.entry.resolve()),
                    readable=str(submission.path.resolve()),
                    # a name that says nothing: the brick's scratch folder is inside, in its sight
                    folder=str(workdir / secrets.token_hex(8)),
                    lesson=lesson_folder,
                    variant_name=variant.name,
                    time_s=variant.time_s,
                    seed=variant.seed,
                    program_seed=lesson.variants[0].seed,
                    hang_s=lesson.limits.hang_s,
                    wall_s=lesson.limits.wall_for(variant.time_s),
                    cpu_s=lesson.limits.cpu_for(variant.time_s),
                    memory_mb=lesson.limits.memory_mb,
                    output_mb=lesson.limits.output_mb,
                    keep_trace=on_failed_run is not None,
                )
            )
    if results_file is not None and (done or not submissions):
        write_results(results_file, lesson, [done[i] for i in sorted(done)], isolation, signing_key)
    for index in sorted(done):
        if on_result is not None:
            on_result(done[index])

    running: list[RunningJob] = []
    cores = CoreShare(jobs)
    zygote = _start_zygote() if use_fork else None
    queue.reverse()  # pop() from the end: submission by submission, in the order given
    gc.collect()
    gc.freeze()  # a forked worker's collections then skip everything the grader holds: a third faster
    try:
        while queue or running:
            while queue and len(running) < jobs:
                job = queue.pop()
                job.cpu = cores.least_used([w.job.cpu for w in running])
                job.alone = jobs == 1
                running.append(start_job(job, lesson, use_fork, zygote))
            _wait_for_one([w.pid for w in running], POLL_S)
            now = time.monotonic()
            for worker in list(running):
                if not worker.poll():
                    if now > worker.deadline:
                        worker.kill("wall")
                    continue
                running.remove(worker)
                kill_orphans(keep={w.pid for w in running}, everything=True)
                job = worker.job
                outcome = collect(worker)
                variant_result = variant_result_of(lesson, job.variant, outcome)
                entry = pending[job.submission]
                if on_failed_run is not None and outcome.trace_path is not None:
                    on_failed_run(entry.submission, job.variant, outcome.trace_path)
                remove_tree(job.folder)
                entry.variants[job.variant] = variant_result
                if outcome.outcome == "error":
                    entry.unstartable[job.variant] = outcome.message
                if len(entry.variants) == len(lesson.variants):
                    del pending[job.submission]
                    finish(job.submission, entry.result(lesson))
    except KeyboardInterrupt as interrupt:  # (Ctrl+C, or SIGTERM or SIGHUP as the grade command turns them)
        partial = Grading(
            lesson, [done[i] for i in sorted(done)], reused, time.monotonic() - started, isolation
        )
        raise GradingInterrupted(partial, getattr(interrupt, "signal_number", None)) from None
    finally:
        gc.unfreeze()
        for worker in running:
            worker.kill("grading was interrupted")
            worker.reap()
        if zygote is not None:
            zygote.close()
        kill_orphans(everything=True)
        remove_tree(workdir)
    return Grading(lesson, [done[i] for i in sorted(done)], reused, time.monotonic() - started, isolation)
