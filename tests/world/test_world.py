"""The World record: its first start, and regions looked up by name or by point."""

import pytest

from ev3sim2d.world.cell import Cell
from ev3sim2d.world.legend import LegendEntry
from ev3sim2d.world.maze_file import maze_from_text_grid
from ev3sim2d.world.world import DEFAULT_AMBIENT


def test_start_regions_and_defaults():
    world = maze_from_text_grid(
        """
        #####
        #.GG#
        #...#
        #####
        """,
        (1, 1),
        legend={"G": "green"},
    )
    assert world.start == world.starts[0]
    assert world.ambient == DEFAULT_AMBIENT
    assert world.regions == {}
    assert world.source is None and world.text is None


def test_region_lookup():
    world = maze_from_text_grid(
        "#####\n#.GG#\n#...#\n#####", legend={"G": LegendEntry(Cell.floor_color("green"), "goal")}
    )
    assert world.regions_at(25, 25) == ["goal"]
    assert world.regions_at(15, 25) == []
    assert world.region("goal").center() == (30.0, 25.0)
    with pytest.raises(KeyError, match="its regions: goal"):
        world.region("finish")
