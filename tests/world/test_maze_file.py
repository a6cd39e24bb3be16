"""Maze files: the shipped worlds load and make sense, and every broken file names its line and the fix."""

import re
import textwrap
from pathlib import Path

import pytest

from ev3sim2d.world.cell import Cell
from ev3sim2d.world.colors import EV3_COLORS
from ev3sim2d.world.maze_file import (
    find_maze,
    list_shipped_mazes,
    load_maze,
    maze_from_text_grid,
    parse_maze,
    shipped_mazes_dir,
)
from ev3sim2d.world.pose import Pose
from ev3sim2d.world.robot_spec import default_robot
from ev3sim2d.world.source_error import WorldFileError

REPO = Path(__file__).resolve().parents[2]
SHIPPED = [name for name, _ in list_shipped_mazes()]


def yaml_text(text: str) -> str:
    """Inline YAML: line 1 is the first non-empty line."""
    return textwrap.dedent(text).lstrip("\n")


def maze_error(text: str) -> WorldFileError:
    with pytest.raises(WorldFileError) as info:
        parse_maze(yaml_text(text), "bad.yaml")
    assert info.value.path == "bad.yaml"
    return info.value


# -- the shipped worlds -------------------------------------------------------------------------


def test_the_four_shipped_mazes_are_listed_with_titles():
    listed = dict(list_shipped_mazes())
    assert {"empty", "line", "maze", "colors"} <= set(listed)
    assert all(title and title != name for name, title in listed.items())
    assert (shipped_mazes_dir() / "line.yaml").is_file()


@pytest.mark.parametrize("name", SHIPPED)
def test_every_shipped_maze_loads_walled_with_starts_on_floor(name):
    path = find_maze(name)
    world = load_maze(path)
    grid = world.grid
    assert world.name == name and world.title and world.description
    assert world.source == str(path) and world.text == path.read_text()
    assert path.read_text().startswith("#"), "a maze starts with a comment header saying its goal"
    assert world.starts
    for start in world.starts:
        cell = grid.cell_at(start.x_cm, start.y_cm)
        assert cell is not None and not cell.wall
    for col, row, cell in grid.cells():
        if col in (0, grid.width - 1) or row in (0, grid.height - 1):
            assert cell.wall, f"border cell ({col}, {row}) of {name} is not a wall"
    width, height = grid.size_cm
    for region in world.regions.values():
        x0, y0, x1, y1 = region.bounds()
        assert 0 <= x0 < x1 <= width and 0 <= y0 < y1 <= height
    assert world.robot == default_robot()


def test_empty_arena_is_at_least_two_metres_inside_with_the_robot_in_the_middle():
    world = load_maze(find_maze("empty"))
    width, height = world.grid.size_cm
    inside = (width - 2 * world.grid.cell_cm, height - 2 * world.grid.cell_cm)
    assert min(inside) >= 200
    assert world.start == Pose(width / 2, height / 2, 0)
    assert all(
        not cell.wall and cell.reflected == 75
        for c, r, cell in world.grid.cells()
        if 0 < c < 19 and 0 < r < 19
    )


def test_line_start_puts_the_colour_sensor_on_the_left_edge_of_the_line():
    world = load_maze(find_maze("line"))
    start = world.start
    sensor = world.robot.sensor("in3")
    ahead_x, ahead_y = sensor.offset_cm
    assert start.heading_deg == 0
    x, y = start.x_cm + ahead_x, start.y_cm + ahead_y
    left_of_sensor = world.grid.cell_at(x, y + 1)  # heading +x: left is +y
    right_of_sensor = world.grid.cell_at(x, y - 1)
    assert left_of_sensor.color_id == 6 and right_of_sensor.color == "black"
    assert world.region("start").contains(start.x_cm, start.y_cm)


def test_line_is_a_closed_loop_one_piece_of_black():
    grid = load_maze(find_maze("line")).grid
    black = {(c, r) for c, r, cell in grid.cells() if cell.color == "black"}
    first = next(iter(black))
    seen, todo = {first}, [first]
    while todo:
        c, r = todo.pop()
        for step in ((c + 1, r), (c - 1, r), (c, r + 1), (c, r - 1)):
            if step in black and step not in seen:
                seen.add(step)
                todo.append(step)
    assert seen == black
    assert all(
        len({(c + dc, r + dr) for dc, dr in ((1, 0), (-1, 0), (0, 1), (0, -1))} & black) >= 2
        for c, r in black
    )


def test_maze_has_wide_corridors_a_corner_start_and_a_green_goal_in_the_far_corner():
    world = load_maze(find_maze("maze"))
    grid = world.grid
    assert grid.cell_cm * 3 >= 30
    start = world.start
    assert start.x_cm < grid.size_cm[0] / 4 and start.y_cm < grid.size_cm[1] / 4
    goal = world.region("goal")
    gx, gy = goal.center()
    assert gx > grid.size_cm[0] * 3 / 4 and gy > grid.size_cm[1] * 3 / 4
    assert grid.cell_at(gx, gy).color == "green"
    # every floor cell is reachable from the start (so the goal is too)
    floor = {(c, r) for c, r, cell in grid.cells() if not cell.wall}
    first = grid.cell_index_at(start.x_cm, start.y_cm)
    seen, todo = {first}, [first]
    while todo:
        c, r = todo.pop()
        for step in ((c + 1, r), (c - 1, r), (c, r + 1), (c, r - 1)):
            if step in floor and step not in seen:
                seen.add(step)
                todo.append(step)
    assert seen == floor


def test_colors_has_a_patch_and_region_per_ev3_colour_in_front_of_the_robot():
    world = load_maze(find_maze("colors"))
    start = world.start
    for name in EV3_COLORS:
        x, y = world.region(name).center()
        assert world.grid.cell_at(x, y).color == name
        assert y == pytest.approx(start.y_cm, abs=10), "the patches lie on the robot's path"
        assert x > start.x_cm
    greys = [r for r in world.regions if r.startswith("shade-")]
    assert len(greys) >= 3


# -- finding mazes -------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["line", "line.yaml", "mazes/line.yaml"])
def test_find_maze_by_name(name):
    assert find_maze(name).resolve() == shipped_mazes_dir() / "line.yaml"


def test_find_maze_prefers_an_existing_file(tmp_path):
    own = tmp_path / "line.yaml"
    own.write_text("title: mine\n")
    assert find_maze(own) == own
    assert find_maze(str(own)) == own


def test_find_maze_lists_the_shipped_names_when_nothing_matches():
    with pytest.raises(WorldFileError) as info:
        find_maze("lline")
    for name in ("empty", "line", "maze", "colors"):
        assert name in info.value.message


def test_a_missing_file_is_a_world_file_error(tmp_path):
    with pytest.raises(WorldFileError) as info:
        load_maze(tmp_path / "nope.yaml")
    assert "no such file" in info.value.message


# -- reading a good file ---------------------------------------------------------------------


def test_the_example_in_the_docs_loads():
    docs = (REPO / "docs" / "world-files.md").read_text()
    example = re.search(r"## A complete world file\s+```yaml\n(.*?)```", docs, re.S).group(1)
    world = parse_maze(example, "docs-example.yaml")
    assert world.title == "First steps"
    assert world.region("goal").contains(75, 45)
    assert world.region("start_box").contains(*world.grid.cell_center(2, 2))
    assert world.grid.cell_at(65, 25).color == "red"
    assert world.region("danger").contains(65, 25)
    assert world.grid.cell(3, 3) == Cell(wall=True, color="red")
    assert world.grid.cell(3, 2) == Cell.floor_shade(40)
    assert world.start == Pose(15, 15, 0)


def test_a_small_maze_with_every_feature():
    world = parse_maze(
        yaml_text(
            """
            # Reach G.
            title: Small
            cell_cm: 4
            legend:
              G: {shade: 100, region: goal}
            grid:
              - "#####"
              - "#..G#"
              - "#...#"
              - "#####"
            start:
              - {cell: [1, 1], heading_deg: 90}
              - {x_cm: 13, y_cm: 6.5}
            regions:
              goal:
                cells: [[3, 1]]
              parking:
                rects_cm: [[4, 4, 8, 8], [8, 4, 12, 8]]
            ambient: 3
            robot:
              wheel_diameter_mm: 43
              axle_track_mm: 100
              body: {front_cm: 5, back_cm: 5, width_cm: 10}
              motors: [{port: A, wheel: left}, {port: D, wheel: right}]
            """
        ),
        "small.yaml",
    )
    assert world.name == "small" and world.description == "Reach G."
    assert world.starts == [Pose(6, 6, 90), Pose(13, 6.5, 0)]
    goal = world.region("goal")
    assert goal.contains(13, 9) and goal.contains(13, 5) and not goal.contains(9, 9)
    assert world.region("parking").area_cm2() == 32
    assert world.ambient == 3
    assert world.robot.wheel_diameter_mm == 43 and world.robot.left_wheel.port == "outA"
    assert world.grid.to_text() == "#####\n#..G#\n#...#\n#####"


def test_robot_file_relative_to_the_maze(tmp_path):
    robot = (
        (REPO / "ev3sim2d" / "robots" / "ev3-driving-base.yaml")
        .read_text()
        .replace("EV3 driving base", "Mine")
    )
    (tmp_path / "bots").mkdir()
    (tmp_path / "bots" / "mine.yaml").write_text(robot)
    maze = tmp_path / "m.yaml"
    maze.write_text("grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\nrobot: bots/mine.yaml\n")
    assert load_maze(maze).robot.name == "Mine"
    maze.write_text("grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\nrobot: ev3-driving-base\n")
    assert load_maze(maze).robot == default_robot()


def test_maze_from_text_grid_for_tests():
    world = maze_from_text_grid(
        """
        #####
        #.G.#
        #...#
        #####
        """,
        legend={"G": "green"},
    )
    assert world.grid.cell(2, 2).color == "green"
    assert world.start == Pose(25, 15, 0)
    assert maze_from_text_grid("#####\n#...#\n#####", (3, 1)).start == Pose(35, 15, 0)


# -- broken files ------------------------------------------------------------------------------

GOOD_GRID = """\
grid: |
  #####
  #...#
  #...#
  #####
"""


@pytest.mark.parametrize(
    ("text", "line", "column", "words"),
    [
        (
            "grid: |\n  #####\n  #.x.#\n  #####\nstart: {cell: [1, 1]}\n",
            3,
            5,
            ["unknown cell character 'x'", "known characters: # .", "legend:", "x: red"],
        ),
        (
            "grid: |\n  #####\n  #...#\n  #..#\n  #####\nstart: {cell: [1, 1]}\n",
            4,
            7,
            ["row 3", "has 4 cells but the first row has 5"],
        ),
        (
            "grid: |\n  #####\n  #....\n  #####\nstart: {cell: [1, 1]}\n",
            3,
            7,
            ["border cell '.' is not a wall", "border cells must be walls", "write '#'"],
        ),
        ("grid: |\n  #####\n  #. .#\n  #####\nstart: {cell: [1, 1]}\n", 3, 5, ["space is not a cell"]),
        ("grid: |\n  ##\n  ##\nstart: {cell: [1, 1]}\n", 1, None, ["2x2 cells", "at least 3x3"]),
        ("grid: |\n  ###\n\n  #.#\n  ###\nstart: {cell: [1, 1]}\n", 3, None, ["empty line"]),
        ("grid: abc\n", 1, 7, ["'grid' must be rows", "grid: |"]),
        ("grid: ###\n", 1, 6, ["'grid' is empty", "starts a YAML comment", "grid: |"]),
        (
            "grid:\n  - '###'\n  - '#.x'\n  - '###'\nstart: {cell: [1, 1]}\n",
            3,
            8,
            ["unknown cell character 'x'"],
        ),
        (GOOD_GRID + "start: {cell: [0, 2]}\n", 6, 15, ["start cell [0, 2] is a wall", "floor cell"]),
        (GOOD_GRID + "start:\n  cell: [7, 1]\n", 7, 9, ["outside the grid", "columns are 0..4"]),
        (GOOD_GRID + "start: {x_cm: 5, y_cm: 15}\n", 6, None, ["inside the wall cell [0, 1]"]),
        (GOOD_GRID + "start: {x_cm: 15, y_cm: 55}\n", 6, None, ["outside the grid (0..50 x 0..40 cm)"]),
        (
            GOOD_GRID + "start:\n  cell: [1, 1]\n  x_cm: 12\n",
            7,
            None,
            ["either as `cell: [col, row]`", "not both"],
        ),
        (GOOD_GRID + "start:\n  heading_deg: 90\n", 7, None, ["needs a position"]),
        (GOOD_GRID + "start: {x_cm: 15}\n", 6, None, ["missing key 'y_cm'"]),
        (GOOD_GRID + "start: {cell: [1, 1], heading: 90}\n", 6, 23, ["unknown key 'heading'", "heading_deg"]),
        (GOOD_GRID + "start: {cell: [1, 1.5]}\n", 6, 19, ["whole number"]),
        (GOOD_GRID + "start: []\n", 6, 8, ["at least one pose"]),
        (GOOD_GRID, 1, None, ["missing key 'start'", "start: {cell:"]),
        ("title: x\nstart: {cell: [1, 1]}\n", 1, None, ["missing key 'grid'"]),
        ("cell_cm: ten\n" + GOOD_GRID, 1, 10, ["'cell_cm' must be a number (cm), got 'ten'"]),
        ("cell_cm: -4\n" + GOOD_GRID, 1, 10, ["1 to 1000 cm"]),
        ("cel_cm: 4\n" + GOOD_GRID, 1, 1, ["unknown key 'cel_cm'", "did you mean 'cell_cm'", "allowed keys"]),
        (GOOD_GRID + "start: {cell: [1, 1]}\nambient: 300\n", 7, 10, ["light level from 0 to 100"]),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nregions:\n  finish:\n    cells: [[1, 1], [5, 1]]\n",
            9,
            21,
            ["region 'finish' cell [5, 1] is outside the grid"],
        ),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nregions:\n  finish:\n    rect_cm: [10, 10, 5, 30]\n",
            9,
            14,
            ["x0 < x1"],
        ),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nregions:\n  finish:\n    rect_cm: [10, 10, 60, 30]\n",
            9,
            14,
            ["reaches outside the grid"],
        ),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nregions:\n  finish: {}\n",
            8,
            None,
            ["needs `cells` or `rect_cm`"],
        ),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nrobot: nobot.yaml\n",
            7,
            8,
            ["no robot file 'nobot.yaml'", "ev3-driving-base"],
        ),
        (GOOD_GRID + "start: {cell: [1, 1]}\nrobot: [1]\n", 7, 8, ["'robot' must be"]),
        (
            GOOD_GRID + "start: {cell: [1, 1]}\nrobot:\n  wheel_diameter_mm: 56\n  axle_track_mm: 120\n"
            "  body: {front_cm: 9, back_cm: 7, width_cm: 15}\n  motors:\n    - {port: E, wheel: left}\n",
            12,
            14,
            ["unknown motor port 'E'", "outA"],
        ),
        ("- a\n- b\n", 1, 1, ["a maze file is a mapping"]),
        ("grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]\n", 6, 1, ["YAML syntax error"]),
        (
            "grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\nlegend:\n  '#': floor\n",
            7,
            8,
            ["legend entry for '#'"],
        ),
    ],
)
def test_broken_maze_files_name_the_line_and_the_fix(text, line, column, words):
    err = maze_error(text)
    assert (err.line, err.column) == (line, column), str(err)
    for word in words:
        assert word in err.message, str(err)
    assert str(err).startswith(f"bad.yaml:{line}")


def test_an_unknown_cell_character_in_a_grid_list_is_placed_inside_the_quotes():
    err = maze_error('grid:\n  - "###"\n  - "#@#"\n  - "###"\nstart: {cell: [1, 1]}\n')
    assert (err.line, err.column) == (3, 7)
    assert '`"@": red`' in err.message


def test_errors_in_a_separate_robot_file_name_that_file(tmp_path):
    (tmp_path / "bot.yaml").write_text("name: b\nwheel_diameter_mm: big\n")
    maze = tmp_path / "m.yaml"
    maze.write_text("grid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\nrobot: bot.yaml\n")
    with pytest.raises(WorldFileError) as info:
        load_maze(maze)
    assert info.value.path.endswith("bot.yaml") and info.value.line == 2
