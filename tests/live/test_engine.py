"""A live run (ev3sim2d/live/engine.py): paced, paused, stepped, reloaded, with a hand in the world.

Without interventions a live run is the run `run` gives, fingerprint for fingerprint, however it was
paused and stepped; each intervention is in the trace, at its time.
"""

from __future__ import annotations

import textwrap
import time
from pathlib import Path

import pytest

from ev3sim2d.live.engine import FAST_SPEED, LiveError, LiveRun
from ev3sim2d.protocol.stream import can_spin
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.cell import Cell
from ev3sim2d.world.maze_file import find_maze, load_maze
from tests.inline_world import arena

FOLLOWER = Path(__file__).resolve().parents[2] / "examples" / "line_follower.py"

DRIVE = """
    from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
    import time
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.on(30, 30)
    time.sleep(20)
"""


def _wait_for(live: LiveRun, predicate, timeout_s: float = 60.0) -> dict:
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        state = live.state()
        if predicate(state):
            return state
        time.sleep(0.02)
    raise AssertionError(f"not reached: {live.state()}")


@pytest.fixture
def started():
    runs: list[LiveRun] = []

    def _start(programs, world, **options) -> LiveRun:
        paused = options.pop("paused", False)
        live = LiveRun(programs, world, **options)
        live.start(paused=paused)
        runs.append(live)
        return live

    yield _start
    for live in runs:
        live.close()


def test_a_live_run_without_interventions_is_the_run_of_run_however_it_was_paused(started):
    world = load_maze(find_maze("line"))
    alone = run_programs([FOLLOWER], world, time_limit_s=5)
    live = started([FOLLOWER], load_maze(find_maze("line")), speed=None, time_limit_s=5, paused=True)
    _wait_for(live, lambda s: s["status"] == "paused" and s["robots"])
    for ms in (3, 10, 57, 100):  # steps that end between ticks, as a student clicks them
        live.step(ms=ms)
    live.step(ticks=1)
    live.resume()
    _wait_for(live, lambda s: s["status"] == "ended")
    trace = live.close()
    assert trace.fingerprint() == alone.trace.fingerprint()


def test_a_live_run_spins_only_as_fast_as_it_goes_and_is_still_the_run_of_run(started):
    """As fast as it goes (or at FAST_SPEED and more) the simulator and its bricks spin as they wait for each
    other, as `run` has them do; at the clock's pace they sleep until woken (the run waits for the clock
    most of the time).  Neither changes the run."""
    programs = [FOLLOWER, FOLLOWER]
    alone = run_programs(programs, load_maze(find_maze("line-shared")), time_limit_s=3)
    live = started(programs, load_maze(find_maze("line-shared")), speed=1.0, time_limit_s=3, paused=True)
    _wait_for(live, lambda s: s["status"] == "paused" and s["robots"])
    session = live._session

    def spinning() -> list[bool]:
        return [session.spin_s > 0] + [port.channel.spin_s > 0 for port in session.ports]

    can = can_spin()
    assert spinning() == [False, False, False]
    live.set_speed(None)
    assert spinning() == [True, can, can]
    live.set_speed(2.0)
    assert spinning() == [False, False, False]
    live.set_speed(FAST_SPEED)
    assert spinning() == [True, can, can]
    live.set_speed(None)
    live.resume()
    _wait_for(live, lambda s: s["status"] == "ended")
    assert live.close().fingerprint() == alone.trace.fingerprint()


def test_pause_freezes_time_and_resume_goes_on(started):
    live = started([FOLLOWER], load_maze(find_maze("line")), speed=2.0)
    _wait_for(live, lambda s: s["status"] == "running" and s["t_s"] > 0.5)
    paused_at = live.pause()["t_s"]
    time.sleep(0.3)
    assert live.state()["t_s"] == paused_at and live.state()["status"] == "paused"
    live.step(ms=100)
    assert live.state()["t_s"] == pytest.approx(paused_at + 0.1, abs=1e-6)
    live.resume()
    _wait_for(live, lambda s: s["t_s"] > paused_at + 0.5)


def test_a_dragged_robot_drives_on_from_where_it_was_put_and_the_trace_shows_the_jump(started, tmp_path):
    program = tmp_path / "drive.py"
    program.write_text(textwrap.dedent(DRIVE))
    live = started([program], arena(), speed=None, paused=True)
    _wait_for(live, lambda s: s["status"] == "paused" and s["robots"])
    live.step(ms=500)
    live.move_robot(0, 60, 60, 90)  # facing +y now
    with pytest.raises(LiveError, match="wall"):
        live.move_robot(0, 2, 2, 0)
    live.step(ms=1000)
    robot = live.state()["robots"][0]
    assert robot["x_cm"] == pytest.approx(60, abs=0.5) and robot["y_cm"] > 60 + 10
    live.reload()  # the placement is kept: it is where the robot starts now
    robot = _wait_for(live, lambda s: s["run"] == 2 and s["robots"])["robots"][0]
    assert (robot["x_cm"], robot["y_cm"]) == pytest.approx((60, 60))


def test_a_wall_put_in_front_of_a_driving_robot_stops_it(started, tmp_path):
    program = tmp_path / "drive.py"
    program.write_text(textwrap.dedent(DRIVE))
    world = arena()
    live = started([program], world, speed=None, paused=True)
    state = _wait_for(live, lambda s: s["status"] == "paused" and s["robots"])
    x, y = state["robots"][0]["x_cm"], state["robots"][0]["y_cm"]
    cell_cm = world.grid.cell_cm
    col, row = int((x + 40) // cell_cm), int(y // cell_cm)
    for r in (row - 1, row, row + 1):
        live.set_cell(col, r, Cell(wall=True))
    live.step(ms=5000)
    robot = live.state()["robots"][0]
    assert robot["x_cm"] < col * cell_cm, "the robot stopped at the new wall"
    assert any(e[2] == "cell" for e in live._sim.trace.events)


def test_a_program_that_fails_pauses_the_run_with_its_file_and_line(started, tmp_path):
    program = tmp_path / "broken.py"
    program.write_text("import time\ntime.sleep(0.2)\nprint(1 / 0)\n")
    live = started([program], arena(), speed=None)
    state = _wait_for(live, lambda s: s["error"] is not None)
    assert state["error"]["type"] == "ZeroDivisionError" and state["error"]["line"] == 3
    assert state["error"]["file"] == str(program)
    program.write_text("print('fixed')\n")
    live.reload()
    state = _wait_for(live, lambda s: s["run"] == 2 and s["status"] == "ended")
    assert state["error"] is None and [p["text"] for p in state["printed"]] == ["fixed"]


def test_a_robot_put_outside_the_world_or_turned_absurdly_is_refused_and_the_run_goes_on(started, tmp_path):
    """A place the page (or anything with the page's key) asks for is checked before the physics sees it,
    while the run goes and once it is over: outside the world, 1e308 or NaN, a heading beyond a turn."""
    program = tmp_path / "drive.py"
    program.write_text(textwrap.dedent(DRIVE))
    live = started([program], arena(), speed=None, paused=True, time_limit_s=1)
    _wait_for(live, lambda s: s["status"] == "paused" and s["robots"])
    for x, y, heading, said in [
        (1e308, 60, 0, "outside the world"),
        (float("nan"), 60, 0, "outside the world"),
        (60, 60, 1e308, "from -360 to 360"),
        (-5, 60, 0, "outside the world"),
    ]:
        with pytest.raises(LiveError, match=said):
            live.move_robot(0, x, y, heading)
    live.resume()
    _wait_for(live, lambda s: s["status"] == "ended")
    with pytest.raises(LiveError, match="outside the world"):  # (a new run would start from there)
        live.move_robot(0, 1e300, 60, 0)
    live.move_robot(0, 60, 60, 90)
    robot = _wait_for(live, lambda s: s["run"] == 2 and s["robots"])["robots"][0]
    assert (robot["x_cm"], robot["y_cm"]) == pytest.approx((60, 60))
