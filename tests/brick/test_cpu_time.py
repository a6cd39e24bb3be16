"""A program's own lines cost time, as Python on the EV3's 300 MHz ARM spends it (brick/scheduler.py,
CpuTime).

The figure: python-ev3dev2 2.1.0's I/O benchmark on an EV3 (ev3dev/ev3dev-lang-python,
utils/benchmarking/benchmark-results.md, image ev3dev-stretch-ev3-generic-2019-05-29, Python 3.5):
`python3 -m timeit "m.count_per_rot"`, a cached property that does no I/O, "1000 loops, best of 3: 215 usec
per loop"; one such loop is 8 lines (timeit's loop, the property, get_cached_attr_int), so a line costs
215 / 8 = 27 us (LINE_US).  Computing is charged in slices of 5 ms, the time CPython lets a thread hold its
interpreter lock while another waits (sys.getswitchinterval(): 0.005 s since Python 3.2).
"""

import ast
import subprocess
import sys
import textwrap

import pytest

from ev3sim2d.brick.cpu_time import LINE_US, Lines
from ev3sim2d.brick.link import READ_US
from ev3sim2d.brick.scheduler import SWITCH_US
from ev3sim2d.world.button_press import parse_press

BUSY_WAIT = """
    import time
    start = time.time()
    spins = 0
    while time.time() - start < 2:
        spins += 1
    print(round(time.time() - start, 3), spins)
"""


def test_a_busy_wait_on_the_clock_ends_when_its_time_is_up(run):
    """A loop that reads the clock and nothing else spends 2 lines (27 us each) a time round, as on the
    brick (LINE_US: 215 us for 8 lines, python-ev3dev2's benchmark-results.md); it used to spin for ever
    at 0.00 s and be stopped as hung."""
    result = run(BUSY_WAIT)
    assert result.status == "finished", result.reason
    elapsed, spins = result.trace.output[0].text.split()
    assert float(elapsed) == pytest.approx(2.0, abs=SWITCH_US / 1e6)
    assert int(spins) == pytest.approx(2_000_000 / (2 * LINE_US), abs=SWITCH_US / (2 * LINE_US))


def test_a_thread_that_computes_while_the_main_thread_joins_it_takes_its_time(run):
    """`t.start(); t.join()` with a thread that only computes: 20,000 times round a loop of 2 lines is
    40,002 lines of 27 us (benchmark-results.md), 1.08 s on the brick; it used to take no time at all."""
    result = run("""
        import threading, time
        def compute():
            total = 0
            for i in range(20_000):
                total += i
        worker = threading.Thread(target=compute)
        worker.start()
        worker.join()
        print(round(time.monotonic() - 1000, 2))
    """)
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "1.08"


def test_threads_that_compute_share_the_one_processor(run):
    """Two threads computing 0.54 s each end together at about 1.08 s: the EV3 has one core, and CPython
    hands its lock between them every 5 ms (sys.getswitchinterval()); they used to end at 0.00 s."""
    result = run("""
        import threading, time
        ends = {}
        def compute(name):
            total = 0
            for i in range(10_000):
                total += i
            ends[name] = round(time.monotonic() - 1000, 2)
        workers = [threading.Thread(target=compute, args=(name,)) for name in "ab"]
        for worker in workers:
            worker.start()
        for worker in workers:
            worker.join()
        print(sorted(ends.values()))
    """)
    assert result.status == "finished", result.reason
    first, last = eval(result.trace.output[0].text)
    assert 1.0 < first <= last
    assert last == pytest.approx(2 * 20_000 * LINE_US / 1e6, abs=0.02)


def test_a_program_that_only_computes_runs_on_to_the_time_limit(run):
    """`while True: x += 1` moves the brick's clock (27 us a line, benchmark-results.md), so the run ends
    at its time limit, not as hung: the hang watchdog is for a clock that truly stands still."""
    result = run("x = 0\nwhile True:\n    x += 1\n", time_limit_s=3, hang_after_s=1.0)
    assert result.status == "time_limit", result.reason
    assert result.sim_time_s == 3.0


def test_a_menu_that_polls_a_button_without_sleeping_sees_the_press(run):
    """`while not btn.enter: pass`: each look at the buttons costs about 1 ms, as python-ev3dev2 2.1.0's
    Button.buttons_pressed (an ioctl, then a loop over six buttons) does on the brick, so a press
    scripted at 1 s is seen then; the loop used to keep the clock at 0.00 s for ever."""
    result = run(
        """
        import time
        from ev3dev2.button import Button
        btn = Button()
        while not btn.enter:
            pass
        print(round(time.monotonic() - 1000, 2))
        """,
        presses=[parse_press("enter@1")],
    )
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "1.0"


def test_the_shim_and_the_brick_cost_only_what_a_device_access_costs(run):
    """100 reads of a motor's position cost 100 x READ_US (link.py: 2 ms, python-ev3dev2 and sysfs
    included), plus the program's own 201 lines (27 us each: one 5 ms slice); the shim's and the brick's
    own lines are in READ_US already and cost nothing more."""
    result = run("""
        import time
        from ev3dev2.motor import LargeMotor, OUTPUT_B
        motor = LargeMotor(OUTPUT_B)
        start = time.monotonic()
        for _ in range(100):
            motor.position
        print(round(time.monotonic() - start, 4))
    """)
    assert result.status == "finished", result.reason
    assert float(result.trace.output[0].text) == pytest.approx((100 * READ_US + SWITCH_US) / 1e6)


def test_the_programs_own_modules_cost_their_time_too(run, tmp_path):
    """A module beside the program is the program's code (its folder, as brick/identity.py counts it):
    its 40,003 lines cost 1.08 s at 27 us a line (benchmark-results.md); they used to cost nothing."""
    (tmp_path / "helper.py").write_text(
        "def spin(n):\n    total = 0\n    for i in range(n):\n        total += i\n    return total\n"
    )
    result = run("""
        import time
        import helper
        helper.spin(20_000)
        print(round(time.monotonic() - 1000, 2))
    """)
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "1.08"


def test_the_same_computing_program_gives_the_same_run_every_time(run):
    """Lines are counted, not timed: two threads computing and a busy wait give the same record (the
    fingerprint) in two runs."""
    source = """
        import threading, time
        def compute(n):
            total = 0
            for i in range(n):
                total += i * i
            print("computed", n, round(time.monotonic() - 1000, 4))
        threading.Thread(target=compute, args=(7_000,)).start()
        threading.Thread(target=compute, args=(9_000,)).start()
        start = time.time()
        while time.time() - start < 0.5:
            pass
        print("waited", round(time.monotonic() - 1000, 4))
    """
    first, second = run(source), run(source)
    assert first.status == "finished", first.reason
    assert len(first.trace.output) == 3
    assert [o.text for o in first.trace.output] == [o.text for o in second.trace.output]
    assert first.trace.fingerprint() == second.trace.fingerprint()


def count_lines(source: str, *calls: str) -> int:
    """How many lines CpuTime counts running source, then the calls (statements) after it."""
    counted = [0]

    def line() -> bool:
        counted[0] += 1
        return True

    namespace = {"__ev3sim2d_line__": line}
    tree = Lines("__ev3sim2d_line__").visit(ast.parse(textwrap.dedent(source)))
    exec(compile(ast.fix_missing_locations(tree), "<counted>", "exec"), namespace)
    counted[0] = 0
    for call in calls:
        exec(call, namespace)
    return counted[0]


def test_a_line_is_a_statement_or_a_loop_going_round():
    """The unit of LINE_US: python-ev3dev2's benchmark loop (timeit's `for _i in _it: stmt; pass`, the
    count_per_rot property, get_cached_attr_int) counts 8 lines a time round, as sys.settrace counts
    them: 215 us for 8 lines (benchmark-results.md)."""
    benchmark = """
        class Motor:
            def __init__(self):
                self._attr_cache = {"count_per_rot": 360}
                self._count_per_rot = None
            def get_cached_attr_int(self, filehandle, keyword):
                value = self._attr_cache.get(keyword)
                if value is None:
                    (filehandle, value) = self.get_attr_int(filehandle, keyword)
                    self._attr_cache[keyword] = value
                return (filehandle, value)
            @property
            def count_per_rot(self):
                "Returns the number of tacho counts in one rotation of the motor."
                (self._count_per_rot, value) = self.get_cached_attr_int(self._count_per_rot, 'count_per_rot')
                return value
        m = Motor()
        def timeit(_it):
            for _i in _it:
                m.count_per_rot
                pass
    """
    assert count_lines(benchmark, "timeit(range(1000))") == 1 + 8 * 1000
    assert count_lines("def f(n):\n    i = 0\n    while i < n: i += 1\n", "f(5)") == 1 + 6 + 5
    assert count_lines("def f(n):\n    return [k * k for k in range(n)]\n", "f(5)") == 1 + 5
    assert count_lines("g = lambda k: k + 1\n", "g(1)", "g(2)") == 2


def test_ev3sim2d_run_ends_a_busy_wait_when_its_time_is_up(tmp_path):
    """The command as a student runs it: the busy wait of 2 s finishes at 2.00 s (27 us a line,
    benchmark-results.md), where it used to be stopped as hung (exit status 3)."""
    program = tmp_path / "busy.py"
    program.write_text(textwrap.dedent(BUSY_WAIT))
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--time", "10", "--hang-after", "1"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "] 2.0 " in done.stdout
    assert "finished at 2.00 s" in done.stderr
