"""A program reads every clock Python offers it, times every wait, sets a timer: the same in every run.

The same file run twice (`ev3sim2d run`), or graded twice (`ev3sim2d grade`, whose bricks are forked
from a zygote), prints the same lines and scores the same: each clock, CPU time, file time, timeout and
timer follows the brick's virtual clock (ev3sim2d/brick/clocks.py).  Within one run, the second
reading of each clock is the first plus exactly the virtual time waited between them.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tests.grading.lesson_maker import write_lesson, write_program

ROOT = Path(__file__).resolve().parents[2]

READINGS = """\
import builtins
builtins.__ev3sim2d_line__ = True.__bool__  # (its own lines would move the clocks between the readings)
import asyncio
import datetime
import importlib
import importlib.util
import json
import logging
import os
import pathlib
import queue
import random
import resource
import select
import selectors
import signal
import threading
import time
import uuid


def readings():
    found = {}
    for name in sorted(n for n in dir(time) if n.startswith("CLOCK_")):
        clock = getattr(time, name)
        found[f"clock_gettime({name})"] = time.clock_gettime(clock)
        found[f"clock_gettime_ns({name})"] = time.clock_gettime_ns(clock)
        found[f"clock_getres({name})"] = time.clock_getres(clock)
    for clock in range(-40, 40):  # any int: a thread's CPU clock, clocks `time` does not name, none at all
        try:
            found[f"clock_gettime_ns({clock})"] = time.clock_gettime_ns(clock)
        except OSError as err:
            found[f"clock_gettime_ns({clock})"] = f"OSError {err.errno}"
    found["cpu clock of a thread"] = time.clock_gettime(time.pthread_getcpuclockid(threading.get_ident()))
    for name in ("time", "monotonic", "perf_counter", "process_time", "thread_time"):
        found[name] = getattr(time, name)()
        found[name + "_ns"] = getattr(time, name + "_ns")()
        found[f"get_clock_info({name})"] = repr(time.get_clock_info(name))
    found["localtime"] = tuple(time.localtime())
    found["gmtime"] = tuple(time.gmtime())
    found["ctime"] = time.ctime()
    found["strftime"] = time.strftime("%Y-%m-%d %H:%M:%S")
    found["os.times"] = tuple(os.times())
    for who in sorted(n for n in dir(resource) if n.startswith("RUSAGE_")):
        found[f"getrusage({who})"] = tuple(resource.getrusage(getattr(resource, who)))
    found["datetime.now"] = datetime.datetime.now().isoformat()
    found["datetime.now(utc)"] = datetime.datetime.now(datetime.timezone.utc).isoformat()
    found["date.today"] = datetime.date.today().isoformat()
    import _datetime

    found["_datetime.datetime.now"] = _datetime.datetime.now().isoformat()
    found["uuid1"] = str(uuid.uuid1())
    found["getnode"] = uuid.getnode()
    random.seed()
    found["random.seed()"] = random.random()
    found["Random()"] = random.Random().random()
    found["SystemRandom()"] = random.SystemRandom().random()
    found["getloadavg"] = os.getloadavg()
    path = pathlib.Path("written.txt")
    path.write_text("now")
    with open(path) as f:
        found["fstat"] = os.fstat(f.fileno()).st_mtime_ns
    found["stat"] = tuple(getattr(os.stat(path), n) for n in ("st_atime", "st_mtime", "st_ctime", "st_mtime_ns"))
    found["lstat"] = os.lstat(path).st_ctime
    found["getmtime"] = os.path.getmtime(path)
    found["pathlib"] = path.stat().st_mtime
    with os.scandir(".") as entries:
        found["scandir"] = [e.stat().st_mtime for e in entries if e.name == "written.txt"]
    found["the program's file"] = os.stat(__file__).st_mtime
    found["a fresh time module"] = importlib.util.module_from_spec(importlib.util.find_spec("time")).monotonic()
    found["time reloaded"] = importlib.reload(time).monotonic()
    found["threading._time"] = threading._time()
    signal.setitimer(signal.ITIMER_REAL, 100.0)
    found["getitimer"] = signal.getitimer(signal.ITIMER_REAL)
    found["alarm"] = signal.alarm(0)
    found["logging"] = logging.LogRecord("x", 20, "p", 1, "m", None, None).relativeCreated
    return found


def waited(name, wait):
    start = time.monotonic()
    wait()
    return f"waited {name} {time.monotonic() - start:.6f}"


def locked():
    lock = threading.Lock()
    lock.acquire()
    return lock


def condition_wait():
    condition = threading.Condition()
    with condition:
        condition.wait(0.25)


def empty_queue():
    try:
        queue.Queue().get(timeout=0.25)
    except queue.Empty:
        pass


def select_while_a_thread_runs():
    fired = threading.Event()
    threading.Timer(0.1, fired.set).start()
    assert select.select([], [], [], 0.25) == ([], [], []) and fired.is_set()


first = readings()
r, w = os.pipe()
waits = [
    waited("sleep", lambda: time.sleep(0.25)),
    waited("select", lambda: select.select([r], [], [], 0.25)),
    waited("poll", lambda: select.poll().poll(250)),
    waited("epoll", lambda: select.epoll().poll(0.25)),
    waited("selectors", lambda: selectors.DefaultSelector().select(0.25)),
    waited("Event.wait", lambda: threading.Event().wait(0.25)),
    waited("Lock.acquire", lambda: locked().acquire(timeout=0.25)),
    waited("Condition.wait", condition_wait),
    waited("Semaphore.acquire", lambda: threading.Semaphore(0).acquire(timeout=0.25)),
    waited("Queue.get", empty_queue),
    waited("asyncio.sleep", lambda: asyncio.run(asyncio.sleep(0.25))),
    waited("select-beside-a-thread", select_while_a_thread_runs),
]
second = readings()
for key in first:
    print("reading", json.dumps([key, first[key], second[key]]))
for line in waits:
    print(line)
"""

TIMER = """\
import signal, time
print(signal.setitimer(signal.ITIMER_REAL, 0.5, 0.2))
for i in range(20):
    print(i, round(time.monotonic(), 3), signal.getitimer(signal.ITIMER_REAL))
    time.sleep(0.1)
print("never")
"""

# Steers the robot by a digest of every reading: a program that tells two gradings apart by the clock
# scores differently in them.
TELLS_GRADINGS_APART = (
    READINGS
    + """
import hashlib
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

bit = hashlib.sha256(repr((first, second)).encode()).digest()[0] % 2
print("bit", bit)
rotations = 28 / 17.59 if bit else 10 / 17.59
MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(SpeedPercent(40), SpeedPercent(40), rotations)
"""
)

WAITED_S = 12 * 0.25  # what the waits between the two readings add up to


def ev3sim2d(*args, cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=300,
    )


def run_twice(tmp_path: Path, source: str, *options: str) -> tuple[str, str]:
    program = tmp_path / "program.py"
    program.write_text(source)
    outputs = []
    for _ in range(2):
        done = ev3sim2d("run", program, "--time", "10", *options, cwd=tmp_path)
        outputs.append(done.stdout)
        reason = done.stderr.strip().splitlines()[-1]
        outputs.append(reason.split(" (simulated in")[0])  # (the real time it took is the machine's)
    assert outputs[0] == outputs[2], "two runs printed different lines"
    assert outputs[1] == outputs[3]
    return outputs[0], outputs[1]


@pytest.mark.needs_linux("posix_clocks")  # (READINGS: clock_gettime, setitimer, alarm)
def test_every_clock_reads_the_same_in_two_runs_and_moves_with_the_virtual_time(tmp_path):
    printed, reason = run_twice(tmp_path, READINGS)
    assert "finished" in reason, reason
    lines = [line.split("] ", 1)[1] for line in printed.splitlines()]
    readings = {}
    for line in lines:
        if line.startswith("reading "):
            key, first, second = json.loads(line.removeprefix("reading "))
            readings[key] = (first, second)
    assert len(readings) > 100
    moved = {
        "clock_gettime(CLOCK_REALTIME)": 1_735_689_600.0,
        "clock_gettime(CLOCK_MONOTONIC)": 1_000.0,
        "clock_gettime(CLOCK_MONOTONIC_RAW)": 1_000.0,
        "clock_gettime(CLOCK_BOOTTIME)": 1_000.0,
        "clock_gettime(CLOCK_TAI)": 1_735_689_637.0,
        "clock_gettime(CLOCK_PROCESS_CPUTIME_ID)": 0.0,
        "clock_gettime(CLOCK_THREAD_CPUTIME_ID)": 0.0,
        "cpu clock of a thread": 0.0,
        "time": 1_735_689_600.0,
        "monotonic": 1_000.0,
        "perf_counter": 0.0,
        "process_time": 0.0,
        "thread_time": 0.0,
        "a fresh time module": 1_000.0,
        "time reloaded": 1_000.0,
        "threading._time": 1_000.0,
        "logging": 0.0,
    }
    for key, start in moved.items():
        first, second = readings[key]
        if key == "logging":
            first, second = first / 1000, second / 1000  # (milliseconds)
        assert (first, second) == pytest.approx((start, start + WAITED_S), abs=1e-6), key
    for key, (first, second) in readings.items():
        if key.startswith("clock_getres"):
            assert first == second == 1e-6
        if key.startswith("clock_gettime_ns(") and isinstance(first, int):
            assert second - first in (0, int(WAITED_S * 1e9)), key  # a clock, or a fixed number of ns
    assert readings["os.times"] == ([0.0, 0.0, 0.0, 0.0, 1000.0], [3.0, 0.0, 0.0, 0.0, 1003.0])
    user, system, *counters = readings["getrusage(RUSAGE_SELF)"][1]
    assert (user, system, set(counters)) == (3.0, 0.0, {0})
    assert set(readings["getrusage(RUSAGE_CHILDREN)"][1][2:]) == {0}
    assert readings["datetime.now"] == ("2025-01-01T00:00:00", "2025-01-01T00:00:03")
    assert readings["_datetime.datetime.now"] == readings["datetime.now"]
    assert readings["getloadavg"][0] == [0.0, 0.0, 0.0]
    for key in ("stat", "lstat", "getmtime", "pathlib", "the program's file"):
        first, _ = readings[key]
        assert (first if isinstance(first, float) else first[0]) == 1_735_689_600.0, key
    assert readings["getitimer"][0] == [100.0, 0.0] and readings["alarm"][0] == 100
    assert readings["uuid1"][0] != readings["uuid1"][1]  # two readings, later in virtual time
    waits = [line.split() for line in lines if line.startswith("waited ")]
    assert len(waits) == 12
    for _, name, seconds in waits:
        assert seconds == "0.250000", name


@pytest.mark.needs_linux("posix_clocks")
def test_a_timer_ends_the_program_at_the_same_virtual_moment_in_every_run(tmp_path):
    printed, reason = run_twice(tmp_path, TIMER)
    assert "killed by SIGALRM (at 0.50 s)" in reason
    lines = [line.split("] ", 1)[1] for line in printed.splitlines()]
    assert lines[0] == "(0.0, 0.0)"
    assert lines[1:] == [  # (a printed line costs 1 ms)
        "0 1000.001 (0.499, 0.2)",
        "1 1000.102 (0.398, 0.2)",
        "2 1000.203 (0.297, 0.2)",
        "3 1000.304 (0.196, 0.2)",
        "4 1000.405 (0.095, 0.2)",
    ]


@pytest.mark.needs_linux("posix_clocks")
def test_an_alarm_ends_a_program_that_waits_for_ever(tmp_path):
    _, reason = run_twice(tmp_path, "import signal, threading\nsignal.alarm(2)\nthreading.Event().wait()\n")
    assert "killed by SIGALRM (at 2.00 s)" in reason


@pytest.mark.needs_linux("posix_clocks")  # (READINGS)
def test_two_gradings_print_the_same_lines_and_score_the_same(tmp_path):
    lesson = write_lesson(tmp_path / "lesson", time_s=10)
    program = write_program(tmp_path, "student.py", TELLS_GRADINGS_APART)
    results = []
    for i in range(2):
        done = ev3sim2d("grade", lesson, program, "--json", tmp_path / f"r{i}.json", "--quiet", cwd=tmp_path)
        assert done.returncode in (0, 1), done.stderr
        document = json.loads((tmp_path / f"r{i}.json").read_text())
        results.append(document["submissions"])
    assert results[0] == results[1]
    [submission] = results[0]
    visible = submission["variants"][0]
    assert visible["output"][-1].endswith((" bit 0", " bit 1"))
    assert any("waited select 0.250000" in line for line in visible["output"])


def test_the_kernels_clock_files_are_closed_to_the_program(tmp_path):
    landlock = json.loads(ev3sim2d("doctor", "--json", cwd=tmp_path).stdout)["report"].get("landlock", "off")
    if not landlock.startswith("on"):
        pytest.skip(f"Landlock is {landlock} here: /proc stays readable (docs/grading-security.md)")
    source = """\
import os
for path in ("/proc/uptime", "/proc/self/stat", "/proc/self/schedstat", "/proc/stat", "/proc/loadavg",
             "/proc/timer_list", "/proc/driver/rtc", "/sys/class/rtc/rtc0/since_epoch", "/proc/1/stat"):
    try:
        with open(path) as f:
            print(path, "read", f.read(40))
    except OSError as err:
        print(path, "closed")
"""
    printed, _ = run_twice(tmp_path, source)
    for line in printed.splitlines():
        assert line.endswith(" closed"), line


@pytest.mark.needs_linux("select_on_pipes")
def test_a_wait_without_a_timeout_waits_for_a_thread_in_virtual_time_and_for_a_process_in_real_time(tmp_path):
    source = """\
import os, select, subprocess, sys, threading, time
start = time.monotonic()
done = subprocess.run([sys.executable, "-c", "print('from a child')"], capture_output=True, text=True)
print(repr(done.stdout), time.monotonic() - start)  # the clock stood still while the child ran
r, w = os.pipe()
threading.Thread(target=lambda: (time.sleep(0.3), os.write(w, b"x"))).start()
start = time.monotonic()
print(select.select([r], [], []), round(time.monotonic() - start, 3))
"""
    printed, reason = run_twice(tmp_path, source)
    lines = [line.split("] ", 1)[1] for line in printed.splitlines()]
    assert lines[0] == "'from a child\\n' 0.0"
    assert re.fullmatch(r"\(\[\d+\], \[\], \[\]\) 0\.309", lines[1])  # the thread wrote at 0.3 s
    assert "finished" in reason


def test_faulthandlers_timer_and_cprofiles_timings_follow_the_virtual_clock(tmp_path):
    source = """\
import cProfile, faulthandler, io, pstats, time
def work():
    time.sleep(0.2)
profile = cProfile.Profile()
profile.enable()
work()
profile.disable()
out = io.StringIO()
pstats.Stats(profile, stream=out).print_stats()
print([line.split()[3] for line in out.getvalue().splitlines() if "(work)" in line])
faulthandler.dump_traceback_later(0.5, file=open("dump.txt", "w"), exit=True)
for i in range(10):
    print(i)
    time.sleep(0.1)
"""
    printed, reason = run_twice(tmp_path, source)
    lines = [line.split("] ", 1)[1] for line in printed.splitlines()]
    assert lines == ["['0.200']", "0", "1", "2", "3", "4"]
    assert "exit status 1" in reason and "(at 0.70 s)" in reason
