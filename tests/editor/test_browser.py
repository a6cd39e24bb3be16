"""The editor page in headless Chromium: click cells in each mode, drag the robot, undo, save, and read
the saved file back with the world loader.

Debian's `chromium` driven by playwright (never `playwright install`); without it the tests are
skipped, except in CI (CI=true), where .ci/run installs it and they must run.
"""

from pathlib import Path

import pytest

from ev3sim2d.world.cell import WALL, Cell
from ev3sim2d.world.maze_file import load_maze
from tests.headless_chromium import chromium


@pytest.fixture(scope="module")
def browser():
    with chromium() as launched:
        yield launched


@pytest.fixture
def page_on(browser, editor_on):
    pages = []

    def open_page(name):
        editor = editor_on(name)
        page = browser.new_page(
            viewport={"width": 1280, "height": 800}, bypass_csp=True
        )  # for wait_for_function
        errors = []
        page.on("pageerror", lambda err: errors.append(str(err)))
        page.on("requestfailed", lambda request: errors.append(request.url))
        page.goto(editor.url)
        page.wait_for_function("window.ev3edit && window.ev3edit.ready()")
        page.errors = errors
        pages.append(page)
        return editor, page

    yield open_page
    for page in pages:
        page.close()


def click_cell(page, col, row):
    xy = page.evaluate(f"ev3edit.cellXY({col}, {row})")
    page.mouse.click(xy["x"], xy["y"])


def drag(page, start, end, steps=8):
    page.mouse.move(start["x"], start["y"])
    page.mouse.down()
    page.mouse.move(end["x"], end["y"], steps=steps)
    page.mouse.up()


def cell(page, col, row):
    return page.evaluate(f"ev3edit.state().cells[{row}][{col}]")


def message(page):
    return page.inner_text("#message")


def save(page):
    page.keyboard.press("Control+s")
    page.wait_for_function("document.getElementById('message').className !== ''")
    return message(page)


def test_edit_each_mode_undo_and_save(page_on):
    editor, page = page_on("maze")
    # wall / floor: a click toggles, dragging paints
    page.keyboard.press("w")
    click_cell(page, 10, 2)
    assert cell(page, 10, 2)["wall"]
    click_cell(page, 10, 2)
    assert not cell(page, 10, 2)["wall"]
    click_cell(page, 10, 2)
    drag(page, page.evaluate("ev3edit.cellXY(6, 1)"), page.evaluate("ev3edit.cellXY(9, 1)"))
    assert all(cell(page, col, 1)["wall"] for col in range(6, 10))
    # lighten and darken step a floor cell's shade
    page.keyboard.press("d")
    click_cell(page, 12, 2)
    click_cell(page, 12, 2)
    assert cell(page, 12, 2)["shade"] == 78
    page.keyboard.press("l")
    click_cell(page, 12, 2)
    assert cell(page, 12, 2)["shade"] == 89
    # paint colour: key 5 is red; a border wall may change colour
    page.keyboard.press("5")
    click_cell(page, 13, 2)
    page.keyboard.press("2")
    click_cell(page, 0, 3)
    assert cell(page, 13, 2)["color"] == "red"
    assert cell(page, 0, 3) | {"char": None} == {
        "wall": True,
        "shade": None,
        "color": "blue",
        "char": None,
        "region": None,
    }
    # undo and redo
    page.keyboard.press("w")
    click_cell(page, 14, 2)
    assert cell(page, 14, 2)["wall"]
    page.keyboard.press("Control+z")
    assert not cell(page, 14, 2)["wall"]
    page.keyboard.press("Control+y")
    page.keyboard.press("Control+z")
    assert not cell(page, 14, 2)["wall"]
    # robot start: drag it from cell (2, 2) to cell (6, 3), turn it with the handle, then with Q
    page.keyboard.press("r")
    drag(page, page.evaluate("ev3edit.cellXY(2, 2)"), page.evaluate("ev3edit.cellXY(6, 3)"))
    start = page.evaluate("ev3edit.state().starts[0]")
    assert (start["x_cm"], start["y_cm"], start["heading_deg"]) == (65, 35, 90)
    drag(page, page.evaluate("ev3edit.handleXY()"), page.evaluate("ev3edit.pageXY(95, 35)"))
    assert page.evaluate("ev3edit.state().starts[0].heading_deg") == 0
    page.keyboard.press("q")
    assert page.evaluate("ev3edit.state().starts[0].heading_deg") == 15
    # regions: drag over cells, then name it
    page.keyboard.press("g")
    drag(page, page.evaluate("ev3edit.cellXY(1, 5)"), page.evaluate("ev3edit.cellXY(3, 7)"))
    page.fill("#regions li input", "parking")
    page.keyboard.press("Tab")
    assert page.evaluate("ev3edit.state().regions") == [{"name": "parking", "rects": [[10, 50, 40, 80]]}]

    assert "Saved" in save(page)
    assert page.errors == []
    world = load_maze(editor.path)
    grid = world.grid
    assert grid.cell(10, 2) == WALL and all(grid.is_wall(col, 1) for col in range(6, 10))
    assert grid.cell(12, 2) == Cell.floor_shade(89)
    assert grid.cell(13, 2) == Cell.floor_color("red")
    assert grid.cell(0, 3) == Cell(wall=True, color="blue")
    assert not grid.is_wall(14, 2)
    assert (world.start.x_cm, world.start.y_cm, world.start.heading_deg) == (65, 35, 15)
    assert world.regions["parking"].rects == ((10, 50, 40, 80),)
    assert world.regions["goal"].contains(185, 185)  # the legend region is kept
    text = editor.path.read_text()
    assert text.startswith("# A maze of 5 x 5 rooms") and editor.path.with_name("maze.yaml.bak").exists()
    # every other cell is as it was
    original = load_maze(Path(__file__).resolve().parents[2] / "mazes" / "maze.yaml").grid
    changed = {(10, 2), (6, 1), (7, 1), (8, 1), (9, 1), (12, 2), (13, 2), (0, 3)}
    assert all(grid.cell(c, r) == original.cell(c, r) for c, r, _ in grid.cells() if (c, r) not in changed)


def test_a_border_cell_cannot_become_floor(page_on):
    editor, page = page_on("empty")
    before = editor.path.read_bytes()
    page.keyboard.press("w")
    click_cell(page, 0, 5)
    assert "Border cells stay walls" in message(page)
    assert page.get_attribute("#message", "class") == "error"
    assert cell(page, 0, 5)["wall"]
    drag(page, page.evaluate("ev3edit.cellXY(19, 3)"), page.evaluate("ev3edit.cellXY(19, 8)"))
    assert all(cell(page, 19, row)["wall"] for row in range(3, 9))
    assert "Nothing changed" in save(page)
    assert editor.path.read_bytes() == before


def test_a_save_the_server_refuses_shows_why_and_changes_nothing(page_on):
    editor, page = page_on("empty")
    before = editor.path.read_bytes()
    # a page that somehow sends a floor border (e.g. an old page): the server refuses it
    page.evaluate(
        """() => {
        const original = window.fetch;
        window.fetch = (url, options) => {
          if (options && options.body) {
            const body = JSON.parse(options.body);
            body.cells[0][4] = {wall: false, shade: 100, color: null, char: null};
            options = Object.assign({}, options, {body: JSON.stringify(body)});
          }
          return original(url, options);
        };
      }"""
    )
    text = save(page)
    assert text.startswith("Not saved:") and "border cell" in text
    assert page.get_attribute("#message", "class") == "error"
    assert editor.path.read_bytes() == before


def test_resize_and_cell_size(page_on):
    editor, page = page_on("empty")
    page.fill("#grid-width", "10")
    page.fill("#grid-height", "8")
    page.click("#resize")
    page.fill("#cell-cm", "6")
    page.click("#set-cell-cm")
    assert "Saved" in save(page)
    world = load_maze(editor.path)
    assert (world.grid.width, world.grid.height, world.grid.cell_cm) == (10, 8, 6)
    assert all(world.grid.is_wall(c, r) for c, r, _ in world.grid.cells() if c in (0, 9) or r in (0, 7))
    assert not world.grid.is_wall(*world.grid.cell_index_at(world.start.x_cm, world.start.y_cm))
