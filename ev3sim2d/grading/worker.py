"""One student's program in one variant, run and scored by a simulator process of its own.

The parent (`grader.py`) starts a worker per submission and variant: forked
from the grader where the system can fork (fast: the lesson and its worlds are
already loaded), else a fresh `python -m ev3sim2d.grading.worker JOB.json`.  The worker
is a simulator: it never runs the student's code itself.  It
- gets a process group of its own (so the parent can end it), and is a child
  subreaper, so that nothing the brick starts can outlive the run,
- sends the console (fds 1 and 2) to a file in its job folder,
- runs `run_programs`, which runs the program in a sandboxed brick process with the
  lesson's limits (CPU time, memory, file sizes, processes) and may read only the
  submission (file or folder) besides Python itself; in a lesson with other robots
  (`others:`), each of the lesson's programs drives its robot from a brick of its own
  that may read only that program's file,
- scores the run with the lesson's checks (which read only the simulator's trace and
  the world), and writes `result.json` (the variant's result), and, when the parent
  asks for failed runs' traces, `trace.npz`; then ends with os._exit.
The job folder, the lesson and the hidden variants are out of the brick's reach.
The parent kills the worker at the wall-clock limit, and reads whatever is left:
`collect()` turns it into a `JobOutcome` (the variant's result, or why there is none).
"""

from __future__ import annotations

import faulthandler
import io
import json
import os
import signal
import subprocess
import sys
import time
import traceback
from dataclasses import asdict, dataclass
from pathlib import Path

from ..results.output_files import write_file
from ..simulator import job_object
from ..simulator.bricks import become_subreaper, die_with_parent, kill_orphans
from ..simulator.scratch import open_console, tail
from .result import VariantResult, printed_output

RESULT_FILE = "result.json"
TRACE_FILE = "trace.npz"
CONSOLE_FILE = "console.log"
EXIT_MEMORY = 3
EXIT_INTERNAL = 4
EXIT_CHECK_ERROR = 5
KEEP_CONSOLE_BYTES = 2000
WORKER_MEMORY_MB = 2048  # a worker's own ceiling (the brick's program has the lesson's memory_mb)

SIGNAL_NAMES = {
    "SIGSEGV": "a segmentation fault",
    "SIGABRT": "an abort",
    "SIGBUS": "a bus error",
    "SIGILL": "an illegal instruction",
    "SIGFPE": "a floating point exception",
    "SIGKILL": "SIGKILL",
    "SIGTERM": "SIGTERM",
}


@dataclass
class Job:
    """One submission in one variant: what to run, where, and within which limits."""

    submission: int
    variant: int
    entry: str
    folder: str  # the job's own folder: result, trace, console
    lesson: str  # the lesson folder (a spawned worker reads the lesson again)
    variant_name: str
    time_s: float
    seed: int
    hang_s: float
    wall_s: float
    cpu_s: float
    memory_mb: float
    output_mb: float
    keep_trace: bool = False  # write trace.npz when a check fails
    readable: str = ""  # the submission (file or folder): all the brick may read besides Python
    program_seed: int = 0  # the program's `random`: the same in every variant, so it cannot tell them apart
    cpu: int | None = None  # the core the worker and its brick share (None: any, and they may spin)
    alone: bool = False  # the only run on the machine now (one job at a time): its processes may choose cores
    grader: int = 0  # the grader's pid: the worker ends when it does


@dataclass
class JobOutcome:
    """What a worker left: the variant's result (`ran`), or why there is none (timeout, memory, output,
    crashed, error: the program could not be started)."""

    outcome: str  # ran, error, timeout, memory, output, crashed
    message: str
    variant: VariantResult | None = None
    trace_path: Path | None = None  # the run's trace, when kept
    wall_s: float = 0.0


class CheckError(RuntimeError):
    """A check raised an exception while scoring a run: a bug in the check (or in a lesson's check_*.py)."""


# -- the child side -------------------------------------------------------------------------


def _limit(which: int, soft: int, hard: int | None = None) -> None:
    import resource

    hard = soft if hard is None else hard
    try:
        _, current_hard = resource.getrlimit(which)
        if current_hard != resource.RLIM_INFINITY:
            soft, hard = min(soft, current_hard), min(hard, current_hard)
        resource.setrlimit(which, (soft, hard))
    except (ValueError, OSError):
        pass  # a limit the system will not set: the parent's wall-clock limit still holds


def _set_limits(job: Job) -> None:
    """The worker's own limits (the student's program has its brick's): no core dumps, and a memory
    ceiling of its own (WORKER_MEMORY_MB above what it has now), so that one run can never take the
    machine.  (Windows: the grader's Job Object for the worker holds its ceiling.)"""
    try:
        import resource
    except ImportError:
        return
    _limit(resource.RLIMIT_CORE, 0)
    if hasattr(resource, "RLIMIT_AS"):
        _limit(resource.RLIMIT_AS, _address_space() + WORKER_MEMORY_MB * 2**20)


def _address_space() -> int:
    """What this process has mapped now, in bytes (0 where the system does not say)."""
    try:
        with open("/proc/self/statm", "rb") as f:
            return int(f.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, AttributeError):
        return 0


def _pin(job: Job) -> None:
    """Keep the worker and its brick (which inherits this) on one core when runs share the cores: they
    take turns, and handing the turn over on one core costs a sixth of waking a process on another
    (benchmarks/grade.py)."""
    if job.cpu is not None and hasattr(os, "sched_setaffinity"):
        try:
            os.sched_setaffinity(0, {job.cpu})
        except OSError:
            pass


def _redirect_console(folder: Path) -> None:
    """fds 1 and 2 (and so anything written to them, by Python or not) into the job's console file."""
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError):
            pass
    fd = open_console(folder / CONSOLE_FILE)
    os.dup2(fd, 1)
    os.dup2(fd, 2)
    os.close(fd)
    null = os.open(os.devnull, os.O_RDONLY)
    os.dup2(null, 0)
    os.close(null)
    # the streams Python writes to may not be fds 1 and 2 (a test runner's capture): make them so
    sys.stdout = io.TextIOWrapper(os.fdopen(1, "wb", closefd=False), "utf-8", "replace", line_buffering=True)
    sys.stderr = io.TextIOWrapper(
        os.fdopen(2, "wb", closefd=False), "utf-8", "backslashreplace", line_buffering=True
    )
    faulthandler.enable(file=sys.stderr)  # a crash's traceback goes to the console file too


def _write_json(path: Path, data: dict) -> None:
    write_file(path, json.dumps(data, default=str))


def run_job(job: Job, lesson, zygote=None) -> None:
    """The worker's whole life (in the child process): limits, run, score, files, exit.  Never returns."""
    code = 0
    folder = Path(job.folder)
    try:
        _redirect_console(folder)
        die_with_parent(job.grader)
        become_subreaper()
        _set_limits(job)
        _pin(job)
        code = _run_and_score(job, lesson, folder, zygote)
    except MemoryError:
        code = EXIT_MEMORY
    except BaseException:  # noqa: BLE001 - whatever it is, the parent reads it from the console file
        try:
            traceback.print_exc()
        except BaseException:  # noqa: BLE001
            pass
        code = EXIT_INTERNAL
    finally:
        try:
            sys.stdout.flush()
            sys.stderr.flush()
        except BaseException:  # noqa: BLE001
            pass
        os._exit(code)


def _run_and_score(job: Job, lesson, folder: Path, zygote=None) -> int:
    from ..simulator.bricks import BrickLimits
    from ..simulator.program import ProgramError
    from ..simulator.run import run_programs, start_failure
    from .run_record import RunRecord
    from .scoring import score_run

    variant = lesson.variants[job.variant]
    world = variant.world()
    limits = BrickLimits(
        cpu_s=max(1, int(job.cpu_s)), memory_mb=int(job.memory_mb), file_mb=max(1, int(job.output_mb))
    )
    # the student's program drives the student's robot and may read only the submission; each of the
    # lesson's own programs (other robots) only its own file
    submission = Path(job.readable or Path(job.entry).parent)
    readable = variant.readable(submission)
    programs = variant.programs(Path(job.entry))
    try:
        result = run_programs(
            programs,
            world,
            None,
            job.time_s,
            job.seed,
            job.hang_s,
            None,
            None,
            readable,
            limits,
            scratch_in=folder,
            program_seed=job.program_seed,
            spin=job.cpu is None,
            zygote=zygote,
            place=job.alone,
        )
    except ProgramError as err:
        _write_json(folder / RESULT_FILE, {"outcome": "error", "message": str(err)})
        return 0
    finally:
        kill_orphans()
    unstartable = start_failure(result)
    if unstartable is not None:  # (its brick could not compile it: a syntax error, with its line)
        _write_json(folder / RESULT_FILE, {"outcome": "error", "message": unstartable})
        return 0
    if result.limit in ("cpu", "output"):
        what = {
            "cpu": ("timeout", f"the program used more than {job.cpu_s:g} s of CPU time, so it was stopped"),
            "output": (
                "output",
                f"the program wrote more than {job.output_mb:g} MB, so it was stopped (output that never ends?)",
            ),
        }[result.limit]
        _write_json(folder / RESULT_FILE, {"outcome": what[0], "message": what[1]})
        return 0
    if result.status == "crashed" and result.limit is None:
        _write_json(folder / RESULT_FILE, {"outcome": "crashed", "message": result.reason})
        return 0
    lesson_program = _lesson_program_failure(result, variant)
    if lesson_program is not None:  # the lesson's bug, not the student's: said loudly, never scored
        _write_json(folder / RESULT_FILE, {"outcome": "crashed", "message": lesson_program})
        return 0
    out_of_memory = result.limit == "memory"
    record = RunRecord(result.trace, world, variant.time_s, variant.student_index)
    try:
        scored = score_run(lesson, job.variant, record, out_of_memory)
    except Exception:  # noqa: BLE001 - a check's bug, not the program's: the parent says so loudly
        traceback.print_exc()
        return EXIT_CHECK_ERROR
    if not variant.hidden:  # what the program printed: a teacher sees why it did what it did (result.py)
        dropped = int(result.trace.result.get("dropped_output_lines") or 0)
        scored.output, scored.output_trimmed, scored.output_lines_dropped = printed_output(
            result.trace.output, variant.student_index, dropped
        )
    kept = job.keep_trace and not scored.passed
    if kept:
        result.trace.save(folder / TRACE_FILE)
    outcome = "memory" if out_of_memory else "ran"
    _write_json(
        folder / RESULT_FILE,
        {"outcome": outcome, "variant": scored.to_dict(), "trace": kept, "wall_time_s": result.wall_time_s},
    )
    return 0


def _lesson_program_failure(result, variant) -> str | None:
    """Why one of the lesson's own programs (another robot's) stopped with an error, if it did."""
    error = result.error or {}
    if not variant.others or "robot" not in error:
        return None
    index = int(str(error["robot"]).removeprefix("robot")) - 1  # run_programs names them robot1, robot2, ...
    if index == variant.student_index:
        return None
    name = variant.robot_names[index]
    return f"the lesson's own program for the robot '{name}' stopped with an error: {error.get('type')}"


# -- the parent side ------------------------------------------------------------------------


class RunningJob:
    """A worker process the parent watches: poll it, kill it at its deadline."""

    def __init__(self, job: Job, pid: int | None = None, popen: subprocess.Popen | None = None) -> None:
        self.job = job
        self.pid = pid if pid is not None else popen.pid
        self.popen = popen
        self.started = time.monotonic()
        self.deadline = self.started + job.wall_s
        self.killed_for: str | None = None
        self.returncode: int | None = None
        self.job_object: job_object.JobObject | None = None  # (Windows) its ceiling; closing it ends it

    def poll(self) -> bool:
        """Whether the worker has ended (reaping it, and ending anything it left behind)."""
        if self.returncode is not None:
            return True
        if self.popen is not None:
            code = self.popen.poll()
            if code is None:
                return False
            self._end_group()
            self.returncode = code
            return True
        if hasattr(os, "waitid"):
            # look without reaping first: while the child is a zombie its group id cannot be reused
            if os.waitid(os.P_PID, self.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is None:
                return False
            self._end_group()
            _, status = os.waitpid(self.pid, 0)
        else:
            pid, status = os.waitpid(self.pid, os.WNOHANG)
            if pid == 0:
                return False
            self._end_group()
        self.returncode = os.waitstatus_to_exitcode(status)
        return True

    def kill(self, reason: str) -> None:
        """End the worker and its process group now (at the wall-clock limit, or when grading stops)."""
        if self.killed_for is None:
            self.killed_for = reason
        self._end_group()
        try:
            if self.popen is not None:
                self.popen.kill()
            else:
                os.kill(self.pid, signal.SIGKILL)
        except (ProcessLookupError, OSError):
            pass

    def reap(self, timeout_s: float = 2.0) -> None:
        """Wait (briefly) for a killed worker to be gone, so it leaves no zombie behind."""
        end = time.monotonic() + timeout_s
        while not self.poll() and time.monotonic() < end:
            time.sleep(0.01)

    def _end_group(self) -> None:
        """Everything the worker started ends with it (its process group; on Windows its Job Object)."""
        if self.job_object is not None:
            self.job_object.close()
        if hasattr(os, "killpg"):
            try:
                os.killpg(self.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError, OSError):
                pass


def start_job(job: Job, lesson, use_fork: bool, zygote=None) -> RunningJob:
    """Start a worker for the job; with use_fork, the child runs `run_job(job, lesson)` straight away,
    with the class run's brick zygote, if it has one."""
    Path(job.folder).mkdir(parents=True, exist_ok=True)
    if use_fork:
        sys.stdout.flush()
        sys.stderr.flush()
        job.grader = os.getpid()
        pid = os.fork()
        if pid == 0:  # the child
            try:
                os.setpgid(0, 0)
            except OSError:
                pass
            for name in ("SIGTERM", "SIGHUP"):  # (the grader's handlers end grading, not a worker)
                if hasattr(signal, name):
                    signal.signal(getattr(signal, name), signal.SIG_DFL)
            run_job(job, lesson, zygote)
        try:
            os.setpgid(pid, pid)  # also from here, so a kill can never miss the group
        except OSError:
            pass
        return RunningJob(job, pid=pid)
    job.grader = os.getpid()
    job_file = Path(job.folder) / "job.json"
    write_file(job_file, json.dumps(asdict(job)))
    options: dict = {"stdin": subprocess.DEVNULL, "stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL}
    if hasattr(os, "setsid"):
        options["start_new_session"] = True
    else:
        options["creationflags"] = getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0)
    popen = subprocess.Popen([sys.executable, "-m", "ev3sim2d.grading.worker", str(job_file)], **options)
    running = RunningJob(job, popen=popen)
    if job_object.available():  # the worker's ceiling, and its end with the grader's
        try:
            running.job_object = job_object.JobObject(WORKER_MEMORY_MB + job.memory_mb * 4, 1024, None)
            running.job_object.assign(popen)
        except OSError:
            pass
    return running


def _signal_name(number: int) -> str:
    try:
        return signal.Signals(number).name
    except ValueError:
        return f"signal {number}"


def collect(running: RunningJob) -> JobOutcome:
    """What the ended worker left, as a JobOutcome."""
    job = running.job
    folder = Path(job.folder)
    wall = time.monotonic() - running.started
    if running.killed_for is not None and running.killed_for != "wall":
        return JobOutcome("crashed", f"the run was stopped: {running.killed_for}", wall_s=wall)
    result_path = folder / RESULT_FILE  # written last: if it is there, the run completed
    if result_path.is_file():
        try:
            info = json.loads(result_path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            info = None
        if isinstance(info, dict) and info.get("outcome") in ("error", "timeout", "output", "crashed"):
            return JobOutcome(info["outcome"], str(info.get("message", "")), wall_s=wall)
        if isinstance(info, dict) and info.get("outcome") in ("ran", "memory"):
            try:
                variant = VariantResult.from_dict(info["variant"])
            except (KeyError, TypeError) as err:
                return JobOutcome("crashed", f"the run left an unreadable result ({err})", wall_s=wall)
            trace = folder / TRACE_FILE if info.get("trace") else None
            return JobOutcome(info["outcome"], variant.message, variant, trace, wall)
    if running.killed_for == "wall":
        return JobOutcome(
            "timeout",
            f"the program ran longer than the limit of {job.wall_s:g} s of real time, so it was stopped "
            "(is it computing a lot between two uses of the robot?)",
            wall_s=wall,
        )
    code = running.returncode if running.returncode is not None else 0
    said = tail(folder / CONSOLE_FILE, KEEP_CONSOLE_BYTES)
    if code == EXIT_CHECK_ERROR:
        raise CheckError(f"a check failed while scoring {job.entry} in variant {job.variant_name}:\n{said}")
    if code < 0:
        name = _signal_name(-code)
        if name == "SIGXCPU":
            return JobOutcome(
                "timeout",
                f"the program used more than {job.cpu_s:g} s of CPU time, so it was stopped",
                wall_s=wall,
            )
        if name == "SIGXFSZ":
            return JobOutcome(
                "output",
                f"the program wrote more than {job.output_mb:g} MB to the console, so it was stopped "
                "(output that never ends?)",
                wall_s=wall,
            )
        what = SIGNAL_NAMES.get(name, name)
        return JobOutcome(
            "crashed", f"the Python interpreter running the program crashed ({what}, {name})", wall_s=wall
        )
    if code == EXIT_MEMORY or "MemoryError" in said:
        return JobOutcome(
            "memory", f"the program used more memory than the {job.memory_mb:g} MB it may use", wall_s=wall
        )
    last = said.splitlines()[-1] if said else "no message"
    return JobOutcome("crashed", f"the run ended without a result (exit status {code}: {last})", wall_s=wall)


# -- a spawned worker (systems without fork) ------------------------------------------------


def main(argv: list[str]) -> None:
    job = Job(**json.loads(Path(argv[0]).read_text(encoding="utf-8")))
    from .lesson import load_lesson

    run_job(job, load_lesson(job.lesson))


if __name__ == "__main__":
    main(sys.argv[1:])
