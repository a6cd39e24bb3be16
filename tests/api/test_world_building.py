"""Worlds built in Python (World.from_text, set_cell, add_region) and saved as YAML that loads back the same."""

import pytest

from ev3sim2d import World, load_maze
from ev3sim2d.world import Cell, Pose, WorldFileError

ROOM = """
    ########
    #......#
    #..k...#
    #......#
    ########
"""


def same_world(a: World, b: World) -> bool:
    fields = ("title", "description", "grid", "starts", "regions", "robot", "ambient", "buttons")
    return all(getattr(a, f) == getattr(b, f) for f in fields)


def test_a_world_built_in_python_saves_as_yaml_that_loads_back_equal(tmp_path):
    world = World.from_text(ROOM, cell_cm=12, starts=[(1, 1, 90), Pose(70, 30, 180)], legend={"G": "green"})
    world.set_cell(2, 1, "G")
    world.set_cell(3, 1, "wall")
    world.set_cell(4, 1, Cell.floor_shade(40))
    world.set_cell(5, 3, "5")
    world.add_region("goal", cells=[(6, 1), (6, 2)])
    world.add_region("box", rect_cm=(12, 24, 36, 36))
    world.save(tmp_path / "room.yaml")
    again = load_maze(tmp_path / "room.yaml")
    assert same_world(again, world)
    assert again.grid.cell(2, 1) == Cell.floor_color("green") and again.grid.is_wall(3, 1)
    assert again.regions_at(78, 20) == ["goal"] and again.regions_at(20, 30) == ["box"]
    assert again.starts[1] == Pose(70, 30, 180)


def test_the_yaml_is_a_world_file_a_person_can_read():
    world = World.from_text(ROOM, starts=[(1, 1)], title="A room")
    world.add_region("goal", rect_cm=(60, 10, 70, 20))
    assert world.text.splitlines()[:3] == ['title: "A room"', "cell_cm: 10", "grid: |"]
    assert "  #..k...#" in world.text and "goal:\n    rect_cm: [60, 10, 70, 20]" in world.text


def test_a_change_shows_in_the_text_a_run_records():
    world = World.from_text(ROOM)
    world.set_cell(1, 1, "g")
    assert "#g.....#" in world.text.replace(" ", "")
    assert world.start == Pose(35, 25, 0)  # no start given: the floor cell nearest the middle


def test_mistakes_name_the_fix():
    with pytest.raises(WorldFileError, match="border cell"):
        World.from_text("#####\n#...#\n#....\n#####")
    world = World.from_text(ROOM)
    with pytest.raises(ValueError, match="unknown cell 'purple'"):
        world.set_cell(1, 1, "purple")
    with pytest.raises(IndexError, match="outside the 8x5 grid"):
        world.set_cell(8, 1, ".")
    with pytest.raises(ValueError, match="inside the grid"):
        world.add_region("far", rect_cm=(0, 0, 100, 10))
    world.add_region("goal", cells=[(1, 1)])
    with pytest.raises(ValueError, match="already has a region 'goal'"):
        world.add_region("goal", cells=[(2, 1)])


def test_a_shipped_world_changed_keeps_the_rest_of_its_file(tmp_path):
    from ev3sim2d.world import find_maze

    world = load_maze(find_maze("line"))
    before = world.text
    world.set_cell(1, 1, "r")
    changed = [a for a, b in zip(before.splitlines(), world.text.splitlines(), strict=True) if a != b]
    assert len(changed) == 1
