"""The grid: cells by (col, row) from the bottom-left, by position in cm, walls as rectangles, text dumps."""

import random

import pytest

from ev3sim2d.world.cell import WALL, Cell
from ev3sim2d.world.grid import Grid
from ev3sim2d.world.maze_file import find_maze, list_shipped_mazes, load_maze
from ev3sim2d.world.source_error import WorldFileError

SMALL = """
    #####
    #r..#
    #..b#
    #####
"""


def small() -> Grid:
    return Grid.from_text(SMALL, cell_cm=10)


def test_size_in_cells_and_cm():
    grid = small()
    assert (grid.width, grid.height, grid.cell_cm) == (5, 4, 10.0)
    assert grid.size_cm == (50.0, 40.0)


def test_row_zero_is_the_bottom_text_line():
    grid = small()
    assert grid.cell(3, 1).color == "blue"
    assert grid.cell(1, 2).color == "red"
    assert grid.is_wall(0, 0) and grid.is_wall(4, 3)
    assert not grid.is_wall(2, 1)


def test_cell_at_maps_cm_to_the_cell_that_covers_it():
    grid = small()
    assert grid.cell_at(35, 15).color == "blue"
    assert grid.cell_at(15, 25).color == "red"
    assert grid.cell_at(10, 10) == Cell.floor_shade(100)  # lower-left corner belongs to the cell
    assert grid.cell_at(9.99, 10).wall
    assert grid.cell_at(49.99, 39.99).wall
    assert grid.cell_index_at(35, 15) == (3, 1)


@pytest.mark.parametrize(("x", "y"), [(-0.01, 5), (5, -0.01), (50, 5), (5, 40), (1e9, 1e9)])
def test_cell_at_is_none_outside_the_grid(x, y):
    assert small().cell_at(x, y) is None
    assert small().cell_index_at(x, y) is None


def test_cell_outside_the_grid_is_an_error_not_a_wrap_around():
    grid = small()
    with pytest.raises(IndexError):
        grid.cell(-1, 0)
    with pytest.raises(IndexError):
        grid.cell(5, 0)
    assert not grid.contains(0, 4) and grid.contains(4, 3)


def test_cell_centre_and_rectangle():
    grid = small()
    assert grid.cell_center(1, 2) == (15.0, 25.0)
    assert grid.cell_rect(1, 2) == (10.0, 20.0, 20.0, 30.0)


def test_sensor_tables_are_indexed_row_then_column():
    grid = small()
    reflected = grid.reflected_rows()
    color_ids = grid.color_id_rows()
    raw = grid.raw_rgb_rows()
    for col, row, cell in grid.cells():
        assert reflected[row][col] == cell.reflected
        assert color_ids[row][col] == cell.color_id
        assert raw[row][col] == cell.raw_rgb
    assert color_ids[1][3] == 2 and color_ids[2][1] == 5
    assert isinstance(reflected, list) and isinstance(reflected[0], list)
    assert grid.wall_rows()[0] == [True] * 5


def rasterise(rects, grid):
    """Every cell covered by the rectangles, counted (so overlaps show up as 2)."""
    covered: dict[tuple[int, int], int] = {}
    s = grid.cell_cm
    for x0, y0, x1, y1 in rects:
        assert x0 < x1 and y0 < y1
        for col in range(round(x0 / s), round(x1 / s)):
            for row in range(round(y0 / s), round(y1 / s)):
                assert (col * s, row * s) >= (x0, y0)
                covered[(col, row)] = covered.get((col, row), 0) + 1
    return covered


def check_wall_rectangles(grid):
    rects = grid.wall_rectangles()
    s = grid.cell_cm
    for rect in rects:
        assert all(round(v / s) * s == pytest.approx(v) for v in rect), "rectangles follow cell edges"
    covered = rasterise(rects, grid)
    assert set(covered) == set(grid.wall_cells())
    assert set(covered.values()) <= {1}, "rectangles do not overlap"
    return rects


def test_a_ring_of_walls_is_four_rectangles():
    rects = check_wall_rectangles(small())
    assert len(rects) == 4


def test_wall_rectangles_cover_exactly_the_walls_of_a_random_grid():
    rng = random.Random(7)
    for _ in range(20):
        width, height = rng.randint(3, 25), rng.randint(3, 25)
        rows = [
            [WALL if rng.random() < 0.4 else Cell.floor_shade(100) for _ in range(width)]
            for _ in range(height)
        ]
        check_wall_rectangles(Grid(rows, cell_cm=rng.choice([2.5, 4, 10])))


@pytest.mark.parametrize("name", [name for name, _ in list_shipped_mazes()])
def test_wall_rectangles_of_shipped_mazes_are_exact_and_few(name):
    grid = load_maze(find_maze(name)).grid
    rects = check_wall_rectangles(grid)
    assert len(rects) <= len(grid.wall_cells()) / 4


def test_a_grid_without_walls_has_no_rectangles():
    assert Grid.from_text("...\n...").wall_rectangles() == []


def test_text_dump_is_top_row_first_and_round_trips():
    grid = small()
    assert grid.to_text() == "#####\n#r..#\n#..b#\n#####"
    assert str(grid) == grid.to_text()
    rebuilt = Grid(
        [[grid.cell(col, row) for col in range(grid.width)] for row in range(grid.height)], cell_cm=10
    )
    assert rebuilt.to_text() == grid.to_text()
    assert Grid.from_text(rebuilt.to_text()) == grid


def test_a_shade_without_its_own_character_prints_as_the_nearest_digit():
    grid = Grid([[WALL, Cell.floor_shade(40), Cell.floor_shade(3)]])
    assert grid.to_text() == "#40"


def test_with_cell_gives_a_changed_copy():
    grid = small()
    painted = grid.with_cell(2, 1, Cell.floor_color("green"))
    assert painted.cell(2, 1).color == "green"
    assert grid.cell(2, 1) == Cell.floor_shade(100)
    assert painted.to_text().splitlines()[2] == "#.gb#"
    assert painted != grid


def test_a_grid_cannot_be_changed_from_outside():
    grid = small()
    with pytest.raises(AttributeError):
        grid.width = 3  # type: ignore[misc]
    with pytest.raises(AttributeError):
        grid.extra = 1  # type: ignore[attr-defined]
    grid.reflected_rows()[1][1] = -1.0
    assert grid.cell(1, 1).reflected == 75.0


def test_from_text_accepts_an_extra_legend():
    grid = Grid.from_text("#X#", legend={"X": "shade 40"})
    assert grid.cell(1, 0) == Cell.floor_shade(40)


def test_from_text_names_the_line_and_column_of_an_unknown_character():
    with pytest.raises(WorldFileError) as info:
        Grid.from_text("\n  ###\n  #?#\n  ###\n")
    err = info.value
    assert (err.line, err.column) == (3, 4)
    assert "unknown cell character '?'" in err.message and "legend" in err.message


def test_from_text_refuses_ragged_rows():
    with pytest.raises(WorldFileError) as info:
        Grid.from_text("###\n##\n###")
    assert info.value.line == 2
    assert "has 2 cells but the first row has 3" in info.value.message
