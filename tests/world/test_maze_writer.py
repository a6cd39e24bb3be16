"""Writing an edited world back into its file: the same text when unchanged, exactly the edits otherwise."""

from pathlib import Path

import pytest

from ev3sim2d.world.cell import WALL, Cell
from ev3sim2d.world.maze_file import parse_maze
from ev3sim2d.world.maze_writer import write_maze_text
from ev3sim2d.world.pose import Pose
from ev3sim2d.world.world_json import EditedCell, MazeSource, edited_from_json

MAZES = sorted((Path(__file__).resolve().parents[2] / "mazes").glob("*.yaml"))


@pytest.mark.parametrize("path", MAZES, ids=lambda p: p.stem)
def test_saving_an_unchanged_world_gives_back_the_same_text(path):
    source = MazeSource(path.read_text(), str(path))
    assert write_maze_text(source, source.as_edited()) == source.text


@pytest.mark.parametrize("path", MAZES, ids=lambda p: p.stem)
def test_the_page_json_read_back_is_the_unchanged_world(path):
    source = MazeSource(path.read_text(), str(path))
    data = source.to_json()
    payload = {
        "cell_cm": data["cell_cm"],
        "cells": [
            [{k: c[k] for k in ("wall", "shade", "color", "char")} for c in row] for row in data["cells"]
        ],
        "starts": data["starts"],
        "regions": data["regions"],
    }
    assert write_maze_text(source, edited_from_json(payload)) == source.text


def _source(path):
    path = Path(path)
    return MazeSource(path.read_text(), str(path))


def test_edited_cells_start_and_regions_are_what_the_loader_reads():
    source = _source(MAZES[[p.stem for p in MAZES].index("maze")])
    edited = source.as_edited()
    edited.cells[5][5] = EditedCell(WALL, None)
    edited.cells[6][6] = EditedCell(Cell.floor_shade(33), None)
    edited.cells[7][7] = EditedCell(Cell.floor_color("red"), None)
    edited.cells[1][1] = EditedCell(Cell.floor_shade(40), None)  # no legend character: a new entry
    edited.cells[0][3] = EditedCell(Cell(wall=True, color="blue"), None)  # a blue border wall
    edited.starts = [Pose(55.0, 15.0, 45.0)]
    edited.regions = [("finish", [(10.0, 10.0, 30.0, 20.0)])]
    text = write_maze_text(source, edited)
    world = parse_maze(text, "edited.yaml")
    for row in range(world.grid.height):
        for col in range(world.grid.width):
            assert world.grid.cell(col, row) == edited.cells[row][col].cell, (col, row)
    assert world.starts == [Pose(55.0, 15.0, 45.0)]
    assert world.regions["finish"].rects == ((10.0, 10.0, 30.0, 20.0),)
    assert world.regions["goal"] == source.regions["goal"]  # legend region kept
    # comments and other keys are kept
    assert text.startswith(source.text.split("legend:")[0])
    assert "title: Maze" in text and "  G: {color: green, region: goal}\n" in text


def test_a_painted_cell_never_joins_a_legend_region():
    source = _source(MAZES[[p.stem for p in MAZES].index("maze")])
    edited = source.as_edited()
    edited.cells[1][1] = EditedCell(Cell.floor_color("green"), None)  # 'G' is green but means region goal
    world = parse_maze(write_maze_text(source, edited), "edited.yaml")
    assert world.grid.cell(1, 1) == Cell.floor_color("green")
    assert not world.regions["goal"].contains(15, 15)


def test_a_world_without_legend_gets_one_and_a_flow_legend_becomes_a_block():
    text = "title: t\ngrid: |\n  ###\n  #.#\n  ###\nstart: {cell: [1, 1]}\n"
    source = MazeSource(text, "t.yaml")
    edited = source.as_edited()
    edited.cells[1][1] = EditedCell(Cell.floor_shade(42), None)
    world = parse_maze(write_maze_text(source, edited), "t.yaml")
    assert world.grid.cell(1, 1) == Cell.floor_shade(42)

    text = (
        "legend: {X: red}  # flow\ngrid: |\n  ####\n  #X.#\n  ####\nstart: {cell: [1, 1]}\nextra_comment: 1\n"
    )
    text = text.replace("extra_comment: 1\n", "# the end\n")
    source = MazeSource(text, "t.yaml")
    edited = source.as_edited()
    edited.cells[1][2] = EditedCell(Cell.floor_shade(42), None)
    out = write_maze_text(source, edited)
    world = parse_maze(out, "t.yaml")
    assert world.grid.cell(1, 1) == Cell.floor_color("red")
    assert world.grid.cell(2, 1) == Cell.floor_shade(42)
    assert out.endswith("# the end\n")


def test_grid_written_as_a_list_stays_a_list_and_cell_size_changes():
    text = 'cell_cm: 5  # small\ngrid:\n  - "###"\n  - "#.#"\n  - "###"\nstart:\n  x_cm: 7.5\n  y_cm: 7.5\n'
    source = MazeSource(text, "t.yaml")
    edited = source.as_edited()
    edited.cell_cm = 8
    edited.starts = [Pose(12.0, 12.0, 0.0)]
    edited.cells[1][1] = EditedCell(Cell.floor_color("yellow"), None)
    out = write_maze_text(source, edited)
    assert "cell_cm: 8  # small\n" in out and '  - "#y#"\n' in out
    world = parse_maze(out, "t.yaml")
    assert world.grid.cell_cm == 8 and world.starts == [Pose(12.0, 12.0, 0.0)]


def test_regions_removed_and_resized_grid():
    path = MAZES[[p.stem for p in MAZES].index("empty")]
    source = _source(path)
    edited = source.as_edited()
    edited.regions = []
    edited.cells = [row[:10] for row in edited.cells[:8]]
    for row in range(8):
        edited.cells[row][9] = EditedCell(WALL, None)
    for col in range(10):
        edited.cells[7][col] = EditedCell(WALL, None)
    edited.starts = [Pose(45.0, 45.0, 0.0)]
    out = write_maze_text(source, edited)
    world = parse_maze(out, "e.yaml")
    assert (world.grid.width, world.grid.height) == (10, 8)
    assert world.regions == {} and "regions:" not in out
    assert world.starts == [Pose(45.0, 45.0, 0.0)]
    # (empty.yaml lists its starts, two of them: one start left is still written as a list)
    assert "start:\n  - {x_cm: 45, y_cm: 45, heading_deg: 0}\n" in out


def test_moving_starts_keeps_each_starts_own_robot(tmp_path):
    """A start that names its own robot (`robot: FILE`) keeps it when the editor moves the starts."""
    text = _source(MAZES[[p.stem for p in MAZES].index("empty")]).text
    start = text[text.index("\nstart:") + 1 :]
    start_block = start[: start.index("\n", start.index("heading_deg")) + 1]
    text = text.replace(
        start_block,
        "start:\n"
        "  - {x_cm: 40, y_cm: 40, heading_deg: 0, robot: ev3-driving-base}\n"
        "  - {x_cm: 80, y_cm: 40, heading_deg: 0}\n",
    )
    path = tmp_path / "two.yaml"
    path.write_text(text)
    source = MazeSource(text, str(path))
    edited = source.as_edited()
    edited.starts = [Pose(44.0, 40.0, 90.0), Pose(84.0, 40.0, 0.0)]
    written = write_maze_text(source, edited)
    world = parse_maze(written, str(path))
    assert [p.x_cm for p in world.starts] == [44.0, 84.0]
    assert "robot: ev3-driving-base" in written
    assert len(world.start_robots) >= 1 and world.start_robots[0] is not None
