"""A program still running at the time limit, or stopped as hung, is told where each of its threads was.

The simulator's stop reaches the brick (at its next tick if it computes, at once if it waits for the
world, or through the brick's main thread if the program is stuck outside the simulation); the brick
answers with its end message, whose `threads` say [thread, file, line] of each thread's innermost frame
of the program's own code (brick/scheduler.py `positions`, brick/program.py `ending`); the session waits a
little for it (session.py `_hear_where`) and the reason says it (simulator/run.py `where_text`), as a
traceback would name the place: `prog.py, line 7`.
"""

import re
import subprocess
import sys

from ev3sim2d.simulator.brick_port import said_threads


def test_a_program_running_at_the_time_limit_is_told_where_each_thread_was(run, tmp_path):
    """The main thread reads a motor in a loop (waiting for the world when the stop comes), its thread
    sleeps in a loop: each is named at its own line, in the program (not in the shim's code it called).
    The reason used to say only that the run reached the time limit."""
    result = run(
        """
        import threading, time
        from ev3dev2.motor import LargeMotor, OUTPUT_B
        def blink():
            while True:
                time.sleep(0.3)
        threading.Thread(target=blink, name="blinker", daemon=True).start()
        motor = LargeMotor(OUTPUT_B)
        while True:
            motor.position
        """,
        time_limit_s=2,
    )
    program = tmp_path / "prog1.py"
    assert result.status == "time_limit", result.reason
    assert result.reason == (
        f"ran until the time limit of 2.00 s (its threads were: MainThread at {program}, line 10; "
        f"blinker at {program}, line 6)"
    )


def test_a_program_stuck_outside_the_simulation_is_told_where_it_was_when_stopped_as_hung(run, tmp_path):
    """A real lock taken twice: the program's thread blocks for good with the clock still, and the
    simulator stops it as hung after --hang-after; the brick's main thread answers for it.  The reason
    used to say only that it was hung."""
    result = run(
        """
        import _thread, time
        time.sleep(0.5)
        lock = _thread.allocate_lock()
        lock.acquire()
        lock.acquire()
        """,
        hang_after_s=1.0,
    )
    assert result.status == "hung", result.reason
    assert result.reason.startswith(
        "stopped: the program ran for a while without using the robot or the clock"
    )
    assert result.reason.endswith(f"at 0.50 s (it was at {tmp_path / 'prog1.py'}, line 6)")


def test_a_deadlock_says_where_each_thread_waits(run, tmp_path):
    """Two threads each holding the lock the other wants: the reason names both places, as a student
    would look for them (the deadlock used to be reported with no place at all)."""
    result = run(
        """
        import threading
        a, b = threading.Lock(), threading.Lock()
        def other():
            with b:
                threading.Event().wait(0.1)
                a.acquire()
        threading.Thread(target=other, name="other").start()
        with a:
            threading.Event().wait(0.2)
            b.acquire()
        """
    )
    program = tmp_path / "prog1.py"
    assert result.status == "hung", result.reason
    assert result.reason.endswith(
        f"(a deadlock) at 0.20 s (its threads were: MainThread at {program}, line 11; other at {program}, line 7)"
    ), result.reason


def test_ev3sim2d_run_says_where_a_program_computing_for_ever_was_at_the_time_limit(tmp_path):
    """The command as a student runs it: `while True: x += 1` runs to the time limit (its lines cost
    time), and the last line names its place in the loop: the same place in every run (the brick hears
    the stop at the same point of the program, never more than two ticks ahead of the world)."""
    program = tmp_path / "forever.py"
    program.write_text("x = 0\nwhile True:\n    x += 1\n")
    reasons = []
    for _ in range(2):
        done = subprocess.run(
            [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "2", "--hang-after", "1"],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 0, done.stderr
        reasons.append(done.stderr.strip().splitlines()[-1].split(" (simulated in")[0])
    assert re.fullmatch(
        rf"ev3sim2d: ran until the time limit of 2\.00 s \(it was at {re.escape(str(program))}, line [23]\)",
        reasons[0],
    ), reasons[0]
    assert reasons[1] == reasons[0]


def test_what_a_brick_says_of_its_threads_is_checked():
    """A brick is a student's program: only [text, text, int] entries are kept, cut short, 64 at most."""
    said = {
        "threads": [["MainThread", "p.py", 3], ["x", 1, 2], "nonsense", ["T" * 500, "f.py", 9]] + [[]] * 99
    }
    assert said_threads(said) == [["MainThread", "p.py", 3], ["T" * 100, "f.py", 9]]
    assert said_threads({"threads": [["a", "b", 1]] * 100}) == [["a", "b", 1]] * 64
    assert said_threads({"threads": "everything"}) is None
    assert said_threads("not a dict") is None
