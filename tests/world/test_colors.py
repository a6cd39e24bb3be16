"""The EV3 colour table and what the colour sensor reads on greys and colours."""

import pytest

from ev3sim2d.world.cell import WALL, Cell
from ev3sim2d.world.colors import (
    COLOR_NAMES_BY_ID,
    EV3_COLORS,
    shade_color_id,
    shade_display_rgb,
    shade_raw_rgb,
    shade_reflected,
)


def test_colour_ids_are_the_ones_the_ev3_sensor_reports():
    assert [(c.name, c.id) for c in EV3_COLORS.values()] == [
        ("black", 1),
        ("blue", 2),
        ("green", 3),
        ("yellow", 4),
        ("red", 5),
        ("white", 6),
        ("brown", 7),
    ]
    for color in EV3_COLORS.values():
        assert COLOR_NAMES_BY_ID[color.id].lower() == color.name


def test_reflected_light_values_are_the_modelled_ones():
    reflected = {name: color.reflected for name, color in EV3_COLORS.items()}
    assert reflected == {
        "black": 5,
        "blue": 9,
        "green": 12,
        "yellow": 70,
        "red": 68,
        "white": 75,
        "brown": 16,
    }


def test_raw_rgb_is_in_the_sensor_range_and_white_is_brightest():
    for color in EV3_COLORS.values():
        assert all(0 <= channel <= 1020 for channel in color.raw_rgb)
        assert all(0 <= channel <= 255 for channel in color.display_rgb)
    assert sum(EV3_COLORS["white"].raw_rgb) == max(sum(c.raw_rgb) for c in EV3_COLORS.values())
    red = EV3_COLORS["red"].raw_rgb
    assert red[0] > 3 * red[1] and red[0] > 3 * red[2]


def test_the_table_cannot_be_changed():
    with pytest.raises(TypeError):
        EV3_COLORS["pink"] = EV3_COLORS["red"]  # type: ignore[index]


@pytest.mark.parametrize(("shade", "reflected"), [(0, 5), (50, 40), (100, 75)])
def test_grey_reflects_linearly_from_black_to_white(shade, reflected):
    assert shade_reflected(shade) == pytest.approx(reflected)


@pytest.mark.parametrize(("shade", "color_id"), [(0, 1), (20, 1), (21, 0), (59, 0), (60, 6), (100, 6)])
def test_grey_is_named_black_white_or_no_colour(shade, color_id):
    assert shade_color_id(shade) == color_id


def test_grey_raw_and_display_colours_run_from_black_to_white():
    assert shade_raw_rgb(0) == pytest.approx(EV3_COLORS["black"].raw_rgb)
    assert shade_raw_rgb(100) == pytest.approx(EV3_COLORS["white"].raw_rgb)
    assert shade_display_rgb(0) == (0, 0, 0)
    assert shade_display_rgb(100) == (255, 255, 255)
    assert shade_display_rgb(50) == (128, 128, 128)


def test_a_colour_cell_answers_with_its_colour():
    red = Cell.floor_color("red")
    assert (red.reflected, red.color_id, red.raw_rgb) == (68, 5, EV3_COLORS["red"].raw_rgb)
    assert red.display_rgb == EV3_COLORS["red"].display_rgb


def test_a_shade_cell_answers_as_a_grey():
    grey = Cell.floor_shade(40)
    assert grey.reflected == pytest.approx(33)
    assert grey.color_id == 0
    assert grey.display_rgb == (102, 102, 102)


def test_a_wall_is_dark_grey_unless_painted():
    assert WALL.wall and WALL.color_id == 0 and WALL.display_rgb == (64, 64, 64)
    red_wall = Cell(wall=True, color="red")
    assert red_wall.wall and red_wall.display_rgb == EV3_COLORS["red"].display_rgb


def test_cells_compare_by_what_they_are():
    assert Cell.floor_shade(100) == Cell(wall=False, shade=100.0)
    assert Cell.floor_shade(100) != Cell.floor_color("white")
    assert len({Cell.floor_shade(100), Cell(shade=100), WALL}) == 2


@pytest.mark.parametrize(
    "kwargs",
    [
        {"wall": False},
        {"shade": 10, "color": "red"},
        {"shade": 101},
        {"color": "pink"},
    ],
)
def test_impossible_cells_are_our_bugs_and_fail_loudly(kwargs):
    with pytest.raises(ValueError):
        Cell(**kwargs)
