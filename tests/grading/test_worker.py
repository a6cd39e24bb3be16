"""Programs that misbehave each get a clear result, and never disturb the grading of the others.

All of them are graded in one class run, two at a time, next to good programs; a program whose limit
this system does not have (a memory limit on macOS, a file-size limit on Windows) is left out of it,
since there it would fill the machine's memory or disk, and its test is skipped, naming the limit."""

import os
from pathlib import Path

import pytest

from ev3sim2d.grading.grader import grade
from ev3sim2d.grading.lesson import load_lesson
from ev3sim2d.grading.submission import find_submissions
from tests import linux_features

from .lesson_maker import GOOD, SHORT, write_lesson, write_program

MISBEHAVING = {
    # stuck outside the simulation (a real lock): its clock stands still, and it is stopped as hung
    "gets_stuck.py": (
        "timeout",
        "got stuck",
        "import _thread\nlock = _thread.allocate_lock()\nlock.acquire()\nlock.acquire()\n",
    ),
    # computing in Python moves its clock (27 us a line, as on an EV3): it runs to the lesson's time limit
    "loops_for_ever.py": ("graded", "ran until the time limit of 5.0 s", "while True:\n    pass\n"),
    "memory_blow_up.py": (
        "memory",
        "ran out of memory",
        "x = []\nwhile True:\n    x.append(bytearray(10**7))\n",
    ),
    "calls_sys_exit.py": ("error", "SystemExit: 3", "import sys\nsys.exit(3)\n"),
    "crashes_python.py": ("crashed", "segmentation fault", "import ctypes\nctypes.string_at(0)\n"),
    "endless_output.py": (
        "output",
        "more than 1 MB",
        "import os\nwhile True:\n    os.write(1, b'x' * 65536)\n",
    ),
    "kills_itself.py": ("crashed", "SIGKILL", "import os, signal\nos.kill(os.getpid(), signal.SIGKILL)\n"),
    # a syntax error is found before any run, and said once: tests/grading/test_grade_outputs.py
    "slow_computing.py": (
        "timeout",
        "longer than the limit of 5 s of real time",
        "import time\nwhile True:\n    sum(range(3 * 10**6))\n    time.sleep(0.001)\n",
    ),
}
NEEDS = {  # what of Linux's a misbehaving program's result needs (tests/linux_features.py)
    "memory_blow_up.py": ("memory_limit",),
    "endless_output.py": ("resource_limits",),  # RLIMIT_FSIZE
    "kills_itself.py": ("signals",),
    "crashes_python.py": ("signals",),  # told as the signal that ended the interpreter
}


@pytest.fixture(scope="module")
def class_run(tmp_path_factory):
    root = tmp_path_factory.mktemp("misbehaving")
    lesson = load_lesson(
        write_lesson(root / "lesson", extra="limits: {wall_s: 5, hang_s: 2, output_mb: 1, memory_mb: 128}")
    )
    programs = root / "class"
    write_program(programs, "a_good.py", GOOD)
    for name, (_, _, source) in MISBEHAVING.items():
        if not linux_features.missing(*NEEDS.get(name, ())):
            write_program(programs, name, source)
    write_program(programs, "os_exit.py", GOOD + "import os\nos._exit(0)\n")
    write_program(programs, "z_short.py", SHORT)
    results = grade(lesson, find_submissions([programs]), jobs=2).results
    return {Path(r.submission).name: r for r in results}


def test_good_programs_around_them_are_graded_correctly(class_run):
    good = class_run["a_good.py"]
    assert good.status == "graded" and good.full_marks
    short = class_run["z_short.py"]
    assert short.status == "graded" and short.score == 0 and short.max_score == 10  # the goal is not met
    assert [c.gated for c in short.variants[0].checks] == [False, False, True]  # finished is held back


def test_os_exit_ends_only_the_program(class_run):
    result = class_run["os_exit.py"]
    assert result.status == "graded" and result.full_marks


@pytest.mark.parametrize(
    "name",
    [pytest.param(name, marks=pytest.mark.needs_linux(*NEEDS.get(name, ()))) for name in sorted(MISBEHAVING)],
)
def test_each_misbehaving_program_gets_its_own_clear_result(class_run, name):
    status, words, _ = MISBEHAVING[name]
    result = class_run[name]
    assert result.status == status, result.first_failure()
    assert all(v.status == status for v in result.variants), [(v.status, v.message) for v in result.variants]
    assert words in result.variants[0].message, result.variants[0].message
    assert result.score < result.max_score


@pytest.mark.needs_linux("cpu_limit")
def test_a_cpu_hog_is_stopped_by_the_cpu_limit(tmp_path):
    lesson = load_lesson(
        write_lesson(tmp_path / "lesson", extra="limits: {wall_s: 30, cpu_s: 1, hang_s: 20}")
    )
    # (one long call of compiled code: its clock stands still while it burns real CPU time; a loop in
    # Python would move its clock, and end at the time limit)
    hog = write_program(tmp_path, "hog.py", "sum(range(10**15))\n")
    result = grade(lesson, find_submissions([hog]), jobs=2).results[0]
    assert result.status == "timeout"
    assert "CPU time" in result.variants[0].message


@pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="no CPU affinity here")
def test_a_worker_given_a_core_keeps_to_it_and_so_does_its_brick():
    from ev3sim2d.grading.worker import Job, _pin

    core = min(os.sched_getaffinity(0))
    job = Job(0, 0, "p.py", "f", "l", "v", 1.0, 0, 1.0, 1.0, 1.0, 100, 1, cpu=core)
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # pinning is for good: do it in a child, as a worker does
        _pin(job)
        child = os.fork()  # a brick is a child of its worker
        if child == 0:
            os.write(write, repr(sorted(os.sched_getaffinity(0))).encode())
            os._exit(0)
        os.waitpid(child, 0)
        os._exit(0)
    os.close(write)
    os.waitpid(pid, 0)
    assert os.read(read, 100).decode() == repr([core])
