"""Bricks forked from a zygote (what a class run does) behave exactly as bricks started afresh."""

from __future__ import annotations

import os
import signal
import socket
import time
from pathlib import Path

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.zygote import BrickZygote, ZygoteGone
from ev3sim2d.world.maze_file import find_maze, load_maze

from ..test_determinism import SOURCES

pytestmark = pytest.mark.needs_linux("fork", "unix_sockets")  # a zygote forks, and is handed fds

STEERED = """\
{source}
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor.lego import ColorSensor

print("value", value)
tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor()
for _ in range(50):
    tank.on(SpeedPercent(20 + 40 * value), SpeedPercent(20 + eye.reflected_light_intensity / 5))
"""


@pytest.fixture(scope="module")
def zygote():
    z = BrickZygote()
    yield z
    z.close()


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


@pytest.mark.parametrize("source", ["random_without_seeding", "numpy_default_rng_without_seed", "time_time"])
def test_a_forked_brick_gives_the_run_of_a_fresh_one(zygote, tmp_path, source):
    program = tmp_path / "steered.py"
    program.write_text(STEERED.format(source=SOURCES[source]))
    world = load_maze(find_maze("line"))
    fresh = run_programs([program], world, time_limit_s=3, seed=4)
    first = run_programs([program], world, time_limit_s=3, seed=4, zygote=zygote)
    second = run_programs([program], world, time_limit_s=3, seed=4, zygote=zygote)  # after another brick
    assert fresh.status == first.status == second.status == "finished", (fresh.reason, first.reason)
    assert first.trace.fingerprint() == second.trace.fingerprint() == fresh.trace.fingerprint()
    assert [line.text for line in first.trace.output] == [line.text for line in fresh.trace.output]
    layers = [{k: str(v).split()[0] for k, v in r.items()} for r in (fresh.sandbox[0], first.sandbox[0])]
    assert layers[0] == layers[1]  # every layer on (or off) as for a fresh brick


def test_the_zygote_says_how_a_brick_ended(zygote, tmp_path):
    """A brick killed by a signal is `crashed` with the signal's name, as a fresh brick is."""
    program = tmp_path / "bomb.py"
    program.write_text("import os, signal\nos.kill(os.getpid(), signal.SIGSEGV)\n")
    world = load_maze(find_maze("empty"))
    fresh = run_programs([program], world, time_limit_s=3)
    forked = run_programs([program], world, time_limit_s=3, zygote=zygote)
    assert forked.status == fresh.status == "crashed"
    assert "SIGSEGV" in forked.reason and "SIGSEGV" in fresh.reason


def test_a_brick_whose_simulator_goes_away_is_killed(zygote, tmp_path):
    """A grading worker killed at the wall-clock limit takes its brick with it, as when the brick was its
    child: the zygote sees the worker's end of the reply socket close, and kills the brick."""
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    read, write = os.pipe()
    worker = os.fork()
    if worker == 0:  # a worker: ask for a brick, never welcome it, die
        try:
            a, b = socket.socketpair()
            with open(scratch / "console.log", "wb") as console:
                child = zygote.spawn(scratch, b.fileno(), -1, console.fileno())
            os.write(write, str(child.pid).encode())
        finally:
            os._exit(0)
    os.close(write)
    brick = int(os.read(read, 32))
    os.waitpid(worker, 0)
    deadline = time.monotonic() + 10
    while _alive(brick) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _alive(brick)


def test_closing_the_zygote_ends_it_and_its_bricks(tmp_path):
    z = BrickZygote()
    scratch = tmp_path / "scratch"
    scratch.mkdir()
    a, b = socket.socketpair()
    with open(scratch / "console.log", "wb") as console:
        child = z.spawn(scratch, b.fileno(), -1, console.fileno())
    assert _alive(child.pid) and _alive(z.pid)
    z.close()
    assert z.popen.returncode is not None
    assert child.wait(timeout=5) == -signal.SIGKILL  # it never got a welcome: the zygote killed it
    with pytest.raises(ZygoteGone):
        z.spawn(scratch, b.fileno(), -1, 1)


def test_a_class_run_starts_python_once_for_its_bricks(tmp_path):
    """The point of the zygote: the grader's bricks are forked, not started (one zygote per class run)."""
    from ev3sim2d.grading.grader import grade
    from ev3sim2d.grading.lesson import load_lesson
    from ev3sim2d.grading.submission import find_submissions

    lesson = load_lesson("line-follow")
    solution = Path(lesson.folder) / "solution.py"
    started = []
    import ev3sim2d.simulator.bricks as bricks

    real_popen = bricks.subprocess.Popen

    def counting_popen(argv, **options):
        started.append(argv)
        return real_popen(argv, **options)

    bricks.subprocess.Popen = counting_popen
    try:
        result = grade(lesson, find_submissions([solution]), jobs=2).results[0]
    finally:
        bricks.subprocess.Popen = real_popen
    assert result.score == result.max_score
    assert len(started) == 1 and "zygote" in started[0]  # three bricks, one Python started


HIJACK = """\
import gc, json, os, select, socket
forged = json.dumps({"scratch": "/", "memory": False, "cpus": []}).encode()
candidates = [fd for fd in range(1024)]
for obj in gc.get_objects():  # the zygote's own objects live on in a forked brick's memory
    if isinstance(obj, socket.socket):
        try:
            candidates.append(obj.fileno())
        except OSError:
            pass
sent = answered = 0
for fd in sorted(set(candidates)):
    try:
        s = socket.socket(fileno=os.dup(fd))
    except OSError:
        continue
    mine, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    try:
        socket.send_fds(s, [forged], [theirs.fileno(), 1, theirs.fileno()])
        sent += 1
    except OSError:
        pass
    if select.select([mine], [], [], 0.05)[0]:
        answered += 1
print("sent", sent, "answered", answered)
"""


def _children(pid: int) -> set[int]:
    found = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat", "rb") as f:
                    stat = f.read().decode("latin-1")
            except OSError:
                continue
            if int(stat[stat.rfind(")") + 2 :].split()[1]) == pid:
                found.add(int(entry))
    return found


@pytest.mark.needs_linux("proc")
def test_a_brick_cannot_ask_the_zygote_for_a_brick_of_its_own(zygote, tmp_path):
    """A student who knows the zygote forks bricks from requests on a socket tries every descriptor,
    and every socket object the zygote left in its forked memory, to ask for a brick whose welcome
    it would write itself (no sandbox).  The zygote's socket is not among them: nothing answers,
    and the zygote forks nothing for it."""
    program = tmp_path / "hijack.py"
    program.write_text(HIJACK)
    before = _children(zygote.pid)
    result = run_programs([program], load_maze(find_maze("empty")), time_limit_s=5, zygote=zygote)
    assert result.status == "finished", result.reason
    printed = [line.text for line in result.trace.output]
    assert printed and printed[-1].endswith("answered 0"), printed
    time.sleep(0.2)
    assert _children(zygote.pid) <= before  # no brick left behind, none forked for the student
