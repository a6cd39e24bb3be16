"""A program that formats a time (`logging`'s `%(asctime)s`, `time.strftime`, `datetime`) formats the
virtual one, in UTC, the same in every run; and the clock it reaches through the shim (python-ev3dev2's
`from time import sleep`, passed on by a star import) is the virtual one, in a brick forked from a zygote
as in one started afresh.

Every run starts at 2025-01-01 00:00:00 UTC in virtual time, and the brick's time zone is UTC on every
machine (ev3sim2d/brick/clocks.py, environment.py; the brick's environment says TZ=UTC).  These are the
functions CPython's logging calls: Lib/logging/__init__.py, `class Formatter: converter =
time.localtime`, `formatTime(record, datefmt)`: `ct = self.converter(record.created)`, then
`time.strftime(datefmt, ct)`, or `default_time_format = '%Y-%m-%d %H:%M:%S'` with `default_msec_format
= '%s,%03d'`.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.zygote import BrickZygote
from tests.inline_world import arena

ROOT = Path(__file__).resolve().parents[2]

LOGGING = """\
#!/usr/bin/env python3
import logging, time
logging.basicConfig(format="%(asctime)s %(message)s")
logging.warning("started")
time.sleep(1.25)
logging.warning("turned after %.2f s", 1.25)
"""
LOGGED = [r"2025-01-01 00:00:00,00\d started", r"2025-01-01 00:00:01,25\d turned after 1\.25 s"]


def lines(result, stream: str = "stdout") -> list[str]:
    return [line.text for line in result.trace.output if line.stream == stream]


def match(found: list[str], patterns: list[str]) -> bool:
    """Whether each line is its pattern (a regular expression): the times printed are the virtual ones,
    to the millisecond or so that the program's own lines cost (brick/scheduler.py, CpuTime)."""
    return len(found) == len(patterns) and all(
        re.fullmatch(p, line) for p, line in zip(patterns, found, strict=True)
    )


def test_logging_with_asctime_writes_the_virtual_time(run):
    """logging.basicConfig(format="%(asctime)s %(message)s") (Lib/logging/__init__.py: a StreamHandler on
    sys.stderr with that format): each record's time is formatted by Formatter.formatTime, through
    Formatter.converter, a class attribute that is time.localtime; a replacement of time.localtime that
    became a method there made every such record a "--- Logging error ---" (TypeError)."""
    result = run(LOGGING)
    assert result.status == "finished", result.reason
    assert match(lines(result, "stderr"), LOGGED), lines(result, "stderr")


def test_a_formatter_with_a_datefmt_and_another_converter_formats_the_virtual_time(run):
    """Formatter(fmt, datefmt).formatTime(record, datefmt) is `time.strftime(datefmt, self.converter(
    record.created))`; Formatter.converter is time.localtime, and a program may set it to time.gmtime
    (the logging docs: "To change it for all formatters, ... set the converter attribute in the Formatter
    class"), as the class attribute or an instance's."""
    result = run(
        """\
        import logging, time
        time.sleep(2.5)
        record = logging.LogRecord("robot", logging.INFO, "prog.py", 1, "seen", None, None)
        dated = logging.Formatter("%(asctime)s|%(name)s|%(message)s", datefmt="%d/%m/%Y %H:%M:%S")
        found = [dated.format(record), dated.formatTime(record, "%H:%M:%S"), dated.formatTime(record)]
        found.append(logging.Formatter.converter is time.localtime)
        logging.Formatter.converter = time.gmtime
        found.append(logging.Formatter("%(asctime)s %(message)s").format(record))
        own = logging.Formatter("%(asctime)s")
        own.converter = time.localtime
        found.append(own.format(record))
        for item in found:
            print(item)
        """
    )
    assert result.status == "finished", result.reason
    assert match(
        lines(result),
        [
            r"01/01/2025 00:00:02\|robot\|seen",
            r"00:00:02",
            r"2025-01-01 00:00:02,50\d",
            r"True",
            r"2025-01-01 00:00:02,50\d seen",
            r"2025-01-01 00:00:02,50\d",
        ],
    ), lines(result)


def test_a_file_handler_writes_its_log_beside_the_program(run):
    """logging.FileHandler("robot.log") opens the file in the working folder, the program's own folder
    as on the EV3 (Brickman starts it with `brickrun --directory <its folder>`; simulator/
    working_folder.py); each line carries the virtual time."""
    result = run(
        """\
        import logging, time
        log = logging.getLogger("robot")
        handler = logging.FileHandler("robot.log")
        handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
        log.addHandler(handler)
        log.setLevel(logging.INFO)
        log.info("start")
        time.sleep(0.75)
        log.error("wall")
        handler.close()
        with open("robot.log", encoding="utf-8") as f:
            print(f.read(), end="")
        """
    )
    assert result.status == "finished", result.reason
    assert match(
        lines(result), [r"2025-01-01 00:00:00,00\d INFO start", r"2025-01-01 00:00:00,75\d ERROR wall"]
    ), lines(result)


def test_time_and_datetime_format_the_virtual_time_in_utc(run):
    """time.strftime(format[, t]), ctime([secs]), asctime([t]), localtime([secs]), gmtime([secs]) with
    and without their argument (Python's docs: without one, "the current time as returned by
    localtime() is used"), datetime.datetime.now(), fromtimestamp(), date.today(): the virtual clock, in
    UTC; a datetime prints as `datetime.datetime(...)`, as CPython's does."""
    result = run(
        """\
        import datetime, time
        time.sleep(1.5)
        found = [
            time.strftime("%Y-%m-%d %H:%M:%S %Z"),
            time.strftime("%a %d %b %Y %H:%M", time.gmtime(86400 * 365)),
            time.ctime(),
            time.ctime(0),
            time.asctime(),
            time.asctime(time.localtime(60)),
            tuple(time.localtime(3600.5)),
            tuple(time.gmtime(1_735_689_600)),
            tuple(time.localtime())[:6],
            (time.localtime().tm_zone, time.timezone),
            repr(datetime.datetime.now()),
            repr(datetime.datetime.fromtimestamp(time.time())),
            str(datetime.datetime.fromtimestamp(0)),
            datetime.datetime.now(datetime.timezone.utc).isoformat(),
            repr(datetime.date.today()),
        ]
        for item in found:
            print(item)
        """
    )
    assert result.status == "finished", result.reason
    assert match(
        lines(result),
        [
            r"2025-01-01 00:00:01 UTC",
            r"Fri 01 Jan 1971 00:00",
            r"Wed Jan  1 00:00:01 2025",
            r"Thu Jan  1 00:00:00 1970",
            r"Wed Jan  1 00:00:01 2025",
            r"Thu Jan  1 00:01:00 1970",
            r"\(1970, 1, 1, 1, 0, 0, 3, 1, 0\)",
            r"\(2025, 1, 1, 0, 0, 0, 2, 1, 0\)",
            r"\(2025, 1, 1, 0, 0, 1\)",
            r"\('UTC', 0\)",
            r"datetime\.datetime\(2025, 1, 1, 0, 0, 1, 50\d\d\d\d\)",
            r"datetime\.datetime\(2025, 1, 1, 0, 0, 1, 50\d\d\d\d\)",
            r"1970-01-01 00:00:00",
            r"2025-01-01T00:00:01\.50\d\d\d\d\+00:00",
            r"datetime\.date\(2025, 1, 1\)",
        ],
    ), lines(result)


def test_two_runs_of_a_logging_program_print_the_same_lines(tmp_path):
    """The real `ev3sim2d run` command, twice on one file: the same lines, the virtual times of the run."""
    program = tmp_path / "logs.py"
    program.write_text(LOGGING, encoding="utf-8")
    outputs = []
    for i in range(2):
        summary = tmp_path / f"run{i}.json"
        done = subprocess.run(
            [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "5", "--summary", str(summary)],
            capture_output=True,
            text=True,
            cwd=ROOT,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr
        report = json.loads(summary.read_text())
        assert report["status"] == "finished", report["reason"]
        outputs.append(report["output"])
    assert outputs[0] == outputs[1]
    assert match(outputs[0], LOGGED), outputs[0]


@pytest.mark.needs_linux("fork", "unix_sockets")  # a zygote forks, and is handed fds
def test_the_sleep_a_star_import_of_the_shim_gives_is_virtual_in_a_forked_brick(tmp_path):
    """python-ev3dev2 2.1.0's ev3dev2/sound.py and led.py say `from time import sleep`, so `from
    ev3dev2.sound import *` gives a program time.sleep; a zygote (what `ev3sim2d grade` forks its bricks
    from) imports the shim before a brick's clocks are virtual, and its `sleep` must still be the virtual
    one: two seconds of the run, not two seconds of the grader's time."""
    program = tmp_path / "beeps.py"
    program.write_text(
        "from ev3dev2.sound import *\nimport time\nstart = time.time()\nsleep(2)\nprint(time.time() - start)\n"
    )
    zygote = BrickZygote()
    try:
        forked = run_programs([program], arena(), time_limit_s=10, zygote=zygote)
    finally:
        zygote.close()
    fresh = run_programs([program], arena(), time_limit_s=10)
    assert forked.status == fresh.status == "finished", (forked.reason, fresh.reason)
    assert lines(forked) == lines(fresh)
    assert 2.0 <= float(lines(forked)[0]) < 2.01


def test_a_timer_is_virtual_only_where_the_system_has_both_its_clock_and_its_signal():
    """Feature checks, not system names: a Python with signal.ITIMER_REAL but no SIGALRM (a stand-in for
    Windows that leaves the constant) loads the brick's clocks and leaves that timer out, where it
    failed to start any brick before."""
    code = (
        "import signal\ndel signal.SIGALRM\n"
        "from ev3sim2d.brick import clocks\n"
        "print(signal.ITIMER_REAL in clocks.TIMER_SIGNALS, signal.ITIMER_VIRTUAL in clocks.TIMER_SIGNALS)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["False", "True"]
