"""A live session replayed from its trace (ev3sim2d/live): the renderer shows each cell a hand changed
from the moment it changed, and a robot put elsewhere jumps, its trail not joining the jump."""

from __future__ import annotations

import textwrap

import numpy as np

from ev3sim2d.live.engine import LiveRun
from ev3sim2d.render.frame import FrameRenderer
from ev3sim2d.world.cell import Cell
from tests.inline_world import arena

DRIVE = """
    from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
    import time
    MoveTank(OUTPUT_B, OUTPUT_C).on(30, 30)
    time.sleep(3)
"""


def _live_session(tmp_path):
    program = tmp_path / "drive.py"
    program.write_text(textwrap.dedent(DRIVE))
    world = arena()
    live = LiveRun([program], world, speed=None)
    live.start(paused=True)
    try:
        while live.state()["status"] != "paused":
            pass
        live.step(ms=1000)
        start = live.state()["robots"][0]
        live.set_cell(3, 3, Cell(wall=True))  # far from the robot
        live.move_robot(0, start["x_cm"], start["y_cm"] + 60, 0)
        live.resume()
        while live.state()["status"] != "ended":
            pass
    finally:
        trace = live.close()
    return trace, world, start


def test_a_replay_shows_the_changed_cell_from_its_time_and_the_jump_without_a_trail(tmp_path):
    trace, world, before = _live_session(tmp_path)
    assert [e[2] for e in trace.events if e[2] in ("cell", "place")] == ["cell", "place"]
    renderer = FrameRenderer(trace, (960, 540))
    view = renderer.view
    changed_at = next(e[0] for e in trace.events if e[2] == "cell")
    cell_cm = world.grid.cell_cm
    px, py = view.px(3.5 * cell_cm, 3.5 * cell_cm)
    early = renderer.frame_at(changed_at - 0.5).copy()
    late = renderer.frame_at(trace.times[-1]).copy()
    assert not np.array_equal(early[py, px], late[py, px]), "the new wall is drawn once it is there"
    # halfway along the jump (60 cm straight up): no trail there
    jx, jy = view.px(before["x_cm"] - 2, before["y_cm"] + 30)
    assert np.array_equal(late[jy, jx], early[jy, jx]), "the trail does not join the jump"
