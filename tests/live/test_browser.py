"""The live page in headless Chromium against a real live run: the robot moves on the page, pause freezes
it, resume goes on, reload runs the edited program, a dragged robot drives on from where it was put,
a wall clicked in stops it, a plot draws a curve, and a crash shows file:line.

Debian's `chromium` driven by playwright (never `playwright install`); without it the tests are
skipped, except in CI (CI=true), where .ci/run installs it and they must run.
"""

from __future__ import annotations

import os
import textwrap
import threading
from pathlib import Path

import pytest

from ev3sim2d.live.engine import LiveRun
from ev3sim2d.live.server import LiveServer, LiveWorldFile
from ev3sim2d.world.maze_file import load_maze
from tests.headless_chromium import chromium
from tests.live.test_server import arena_text

DOCS_IMAGE = Path(__file__).resolve().parents[2] / "docs" / "images" / "live.png"

DRIVE = """
    from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
    from ev3dev2.sensor.lego import ColorSensor
    import time
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    light = ColorSensor()
    print("{word}")
    tank.on(20, 20)
    for _ in range(300):
        print(light.reflected_light_intensity)
        time.sleep(0.1)
"""


@pytest.fixture(scope="module")
def browser():
    with chromium() as launched:
        yield launched


@pytest.fixture
def live_page(browser, tmp_path):
    """live_page(program_text, speed=..., paused=...) -> (page, LiveRun, program path)."""
    opened: list = []

    def open_page(program: str = DRIVE.format(word="hello"), speed: float | None = 1.0, paused: bool = False):
        path = tmp_path / "prog.py"
        path.write_text(textwrap.dedent(program))
        world_path = tmp_path / "arena.yaml"
        world_path.write_text(arena_text())
        live = LiveRun([path], load_maze(world_path), speed=speed)
        server = LiveServer(live, LiveWorldFile(world_path))
        threading.Thread(target=server.serve_forever, daemon=True).start()
        live.start(paused=paused)
        page = browser.new_page(viewport={"width": 1280, "height": 800}, bypass_csp=True)
        errors: list[str] = []
        page.on("pageerror", lambda err: errors.append(str(err)))
        page.goto(server.url)
        page.wait_for_function("window.ev3live && window.ev3live.ready()")
        page.errors = errors
        opened.append((server, live, page))
        return page, live, path

    yield open_page
    for server, live, page in opened:
        page.close()
        server.shutdown()
        server.server_close()
        live.close()


def test_the_docs_picture_a_line_follower_with_its_plot(browser, tmp_path):
    """docs/images/live.png: the line follower on the line track, paused, its light and speeds plotted.
    Written into docs/ only when EV3SIM2D_DOCS_PICTURES=1 (a test run must not change the checkout)."""
    root = Path(__file__).resolve().parents[2]
    world_path = root / "mazes" / "line.yaml"
    live = LiveRun([root / "examples" / "line_follower.py"], load_maze(world_path), speed=4.0)
    server = LiveServer(live, LiveWorldFile(world_path))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    live.start()
    page = browser.new_page(viewport={"width": 1280, "height": 800}, bypass_csp=True)
    try:
        page.goto(server.url)
        page.wait_for_function("window.ev3live && window.ev3live.ready()")
        wait_state(page, "s.t_s > 9", timeout_ms=20000)
        page.click("#pause")
        wait_state(page, "s.status === 'paused'")
        page.wait_for_timeout(200)
        shot = tmp_path / "live.png"
        page.screenshot(path=str(shot))
        assert shot.stat().st_size > 20_000
        if os.environ.get("EV3SIM2D_DOCS_PICTURES") == "1":
            DOCS_IMAGE.write_bytes(shot.read_bytes())
    finally:
        page.close()
        server.shutdown()
        server.server_close()
        live.close()


def robot(page) -> dict:
    return page.evaluate("ev3live.state().robots[0]")


def wait_state(page, condition: str, timeout_ms: int = 8000) -> None:
    page.wait_for_function(f"(s => {condition})(ev3live.state())", timeout=timeout_ms)


def drag(page, start, end, steps=8):
    page.mouse.move(start["x"], start["y"])
    page.mouse.down()
    page.mouse.move(end["x"], end["y"], steps=steps)
    page.mouse.up()


def test_the_robot_moves_pause_freezes_it_and_resume_goes_on(live_page):
    page, live, _ = live_page(speed=2.0)
    x0 = robot(page)["x_cm"]
    wait_state(page, f"s.robots[0].x_cm > {x0} + 3")
    page.click("#pause")
    wait_state(page, "s.status === 'paused'")
    page.wait_for_timeout(150)  # the last frames drawn
    stage = page.locator("#stage")
    first = stage.screenshot()
    t_paused = live.state()["t_s"]
    page.wait_for_timeout(400)
    assert stage.screenshot() == first
    assert live.state()["t_s"] == t_paused
    assert page.inner_text("#pause") == "Resume"
    page.click("#pause")
    wait_state(page, f"s.status === 'running' && s.t_s > {t_paused} + 0.3")
    assert stage.screenshot() != first
    assert not page.errors


SAY = """
    import time
    print("{word}")
    time.sleep(30)
"""


def test_reload_after_editing_the_file_runs_the_new_program(live_page):
    page, live, path = live_page(SAY.format(word="hello"))
    page.wait_for_function("document.getElementById('printed').textContent.includes('hello')")
    live.watch = False  # the button, not the file watcher, reloads here
    path.write_text(textwrap.dedent(SAY.format(word="goodbye")))
    page.click("#reload")
    page.wait_for_function("document.getElementById('printed').textContent.includes('goodbye')")
    assert page.evaluate("ev3live.state().run") == 2


def test_a_dragged_robot_is_put_there_and_the_trace_shows_the_jump(live_page):
    page, live, _ = live_page(paused=True)
    drag(page, page.evaluate("ev3live.robotXY(0)"), page.evaluate("ev3live.pageXY(150, 60)"))
    wait_state(page, "Math.abs(s.robots[0].x_cm - 150) < 1 && Math.abs(s.robots[0].y_cm - 60) < 1")
    assert live.state()["interventions"] == 1
    assert [e[2] for e in live._sim.trace.events].count("place") == 1
    # the handle turns it: drag the handle to straight above the robot
    drag(page, page.evaluate("ev3live.handleXY()"), page.evaluate("ev3live.pageXY(150, 100)"))
    wait_state(page, "Math.abs(s.robots[0].heading_deg - 90) < 1")
    page.click("#step")  # the physics takes it from there: it drives up
    wait_state(page, "s.robots[0].y_cm > 60.5")


def test_a_clicked_wall_stops_the_robot(live_page):
    page, live, _ = live_page(paused=True)
    page.keyboard.press("w")
    for row in (9, 10, 11):  # the robot is at (60, 120): cells of 12 cm, column 9 is 48 cm ahead
        page.mouse.click(**page.evaluate(f"ev3live.cellXY(9, {row})"))
    wait_state(page, "s.world_version === 3")
    assert live.world.grid.cell(9, 10).wall
    page.select_option("#speed", "max")
    page.click("#pause")  # it says Resume while paused
    wait_state(page, "s.t_s > 6", timeout_ms=9000)
    assert robot(page)["x_cm"] < 9 * 12, "stopped at the new wall"


def test_a_plot_draws_a_curve(live_page):
    page, _, _ = live_page(speed=5.0)
    page.wait_for_function("ev3live.series().some(s => s.on && s.samples > 20)")
    page.wait_for_timeout(100)
    lit = page.evaluate(
        """() => {
        const c = document.getElementById('plot');
        const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let lit = 0;
        for (let y = 0; y < c.height; y++) for (let x = Math.floor(c.width / 5); x < c.width; x++) {
          const i = (y * c.width + x) * 4;
          if (data[i] + data[i + 1] + data[i + 2] > 250) lit++;
        }
        return lit;
    }"""
    )
    assert lit > 50, "the curves are drawn"


def test_a_crash_shows_file_and_line(live_page):
    page, _, path = live_page("import time\ntime.sleep(0.2)\nprint(1 / 0)\n", speed=None)
    page.wait_for_selector("#error:not([hidden])")
    assert f"{path}:3" in page.inner_text("#error-where")
    assert "ZeroDivisionError" in page.inner_text("#error")


def test_a_sensor_moved_on_the_page_is_applied_and_drawn_there(live_page):
    page, live, _ = live_page(paused=True)
    page.wait_for_function("ev3live.robotEdit() !== null")
    index = page.evaluate("ev3live.robotEdit().mapping.sensors.findIndex(s => s.kind === 'color')")
    row = page.locator("#sensor-editor tr").nth(index + 1)  # after the heading row
    stage = page.locator("#canvas")
    before = stage.screenshot()
    row.locator("input[data-field=radius_cm]").fill("2")
    row.locator("input[data-field=radius_cm]").dispatch_event("change")
    page.click("#apply-robot")
    wait_state(page, "s.run === 2 && s.robots[0].sensors.some(x => x.kind === 'color' && x.radius_cm === 2)")
    assert live.robot_spec(0).sensor("in3").radius_cm == 2
    page.wait_for_timeout(200)
    assert stage.screenshot() != before  # the colour sensor's spot moved in, nearer the robot's centre
    assert page.errors == []


def test_the_brick_shows_its_lights_in_colour_and_its_screen(live_page):
    program = """
        from ev3dev2.display import Display
        from ev3dev2.led import Leds
        import time
        Leds().set_color("LEFT", "RED")
        lcd = Display()
        lcd.draw.rectangle((0, 0, 177, 127), fill="black")
        lcd.update()
        time.sleep(30)
    """
    page, _, _ = live_page(program)
    wait_state(page, "s.robots[0].lcd_frame !== null && s.t_s > 0.5")
    page.wait_for_function(
        "document.querySelector('.led[data-side=left]').style.background === 'rgb(255, 0, 0)'"
    )
    page.wait_for_function(  # the screen's middle is black, as the program drew it
        "document.querySelector('#bricks canvas').getContext('2d').getImageData(89, 64, 1, 1).data[0] < 40"
    )
    assert page.errors == []
