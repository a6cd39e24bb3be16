"""The limits of world and robot files (ev3sim2d/world/file_limits.py), checked where a file is read."""

from __future__ import annotations

import json
import os
import threading

import pytest

from ev3sim2d.world.button_press import parse_press
from ev3sim2d.world.maze_file import parse_maze
from ev3sim2d.world.robot_spec import parse_robot, robot_mapping_text, shipped_robots_dir
from ev3sim2d.world.source_error import WorldFileError
from ev3sim2d.world.world_json import BadEdit, MazeSource, edited_from_json
from ev3sim2d.world.yaml_source import load_yaml_text, read_text_file

BASE_ROBOT = (shipped_robots_dir() / "ev3-driving-base.yaml").read_text()


def world(width: int, height: int, extra: str = "", start: str = "start: {cell: [1, 1]}") -> str:
    rows = ["#" * width] + ["#" + "." * (width - 2) + "#"] * (height - 2) + ["#" * width]
    return "grid: |\n" + "".join(f"  {row}\n" for row in rows) + start + "\n" + extra


def world_error(text: str) -> WorldFileError:
    with pytest.raises(WorldFileError) as caught:
        parse_maze(text, "w.yaml")
    return caught.value


def robot_error(text: str) -> WorldFileError:
    with pytest.raises(WorldFileError) as caught:
        parse_robot(text, "r.yaml")
    return caught.value


def test_a_grid_of_200_cells_each_way_loads_and_one_more_row_or_column_is_refused_at_its_line():
    assert parse_maze(world(200, 200), "w.yaml").grid.width == 200
    err = world_error(world(3, 201))
    assert (err.line, "201 rows" in err.message, "at most 200 cells each way" in err.message) == (
        1,
        True,
        True,
    )
    err = world_error(world(201, 3))
    assert err.line == 2 and "201 cells" in err.message


def test_an_alias_counts_each_time_it_is_used():
    """Ten levels of ten aliases: refused at the alias that passes the limit, before anything is built."""
    lines = ['a0: &a0 "####"'] + [f"a{n}: &a{n} [{', '.join([f'*a{n - 1}'] * 10)}]" for n in range(1, 11)]
    err = world_error("legend:\n  " + "\n  ".join(lines) + "\n")
    assert "more than 100,000 values (aliases counted each time they are used)" in err.message
    assert err.line is not None and err.line <= 7


def test_a_few_aliases_are_fine():
    text = world(5, 5, "regions:\n  goal: &g {cells: [[1, 1]]}\n  home: *g\n")
    assert set(parse_maze(text, "w.yaml").regions) >= {"goal", "home"}


def test_an_alias_inside_its_own_anchor_is_refused():
    err = world_error("title: &t [*t]\n")
    assert "alias" in err.message  # PyYAML's own check or ours: a loop is never composed


def test_nesting_deeper_than_32_is_a_message_not_a_recursion_error():
    err = world_error("title: " + "[" * 3000 + "]" * 3000 + "\n")
    assert (err.line, err.column) == (1, 39) and "nested more than 32 deep" in err.message
    assert load_yaml_text("a: " + "[" * 30 + "]" * 30).is_mapping


def test_a_file_longer_than_its_limit_is_refused_without_reading_it_all(tmp_path):
    big = tmp_path / "big.yaml"
    big.write_text("# x\n" * 300_000)
    with pytest.raises(WorldFileError, match="more than 1,000,000 bytes"):
        read_text_file(big)
    robot = tmp_path / "robot.yaml"
    robot.write_text(BASE_ROBOT + "# x\n" * 70_000)
    from ev3sim2d.world.robot_spec import load_robot

    with pytest.raises(WorldFileError, match="more than 256,000 bytes"):
        load_robot(robot)


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")
def test_a_pipe_in_place_of_a_world_file_is_refused_at_once(tmp_path):
    pipe = tmp_path / "world.yaml"
    os.mkfifo(pipe)
    result: list = []
    reader = threading.Thread(target=lambda: result.append(_error_of(read_text_file, pipe)), daemon=True)
    reader.start()
    reader.join(5)
    assert result and "not a plain file" in str(result[0])


def _error_of(function, *args):
    try:
        function(*args)
    except WorldFileError as err:
        return err
    return None


@pytest.mark.parametrize(
    "extra, words",
    [
        ("cell_cm: 0.001\n", "'cell_cm', the size of a grid cell, must be 1 to 1000 cm"),
        ("cell_cm: 1e300\n", "must be 1 to 1000 cm, got 1e+300"),
        ("title: " + "x" * 201 + "\n", "'title' is 201 characters long"),
        ("buttons: [enter@nan]\n", "at most 86400 s"),
        ("buttons: [enter@1e300]\n", "at most 86400 s"),
        ("buttons: [" + ", ".join(["enter@1"] * 1001) + "]\n", "more than the 1,000"),
        (
            "legend: {" + ", ".join(f'"{chr(0x100 + n)}": wall' for n in range(101)) + "}\n",
            "more than the 100",
        ),
        (
            "regions: {" + ", ".join(f"r{n}: {{cells: [[1, 1]]}}" for n in range(101)) + "}\n",
            "more than the 100",
        ),
        ("regions: {" + "x" * 61 + ": {cells: [[1, 1]]}}\n", "1 to 60 characters"),
        ("robot: " + "a" * 1001 + "\n", "at most 1,000 characters"),
    ],
)
def test_world_numbers_and_counts_out_of_range_name_the_limit(extra, words):
    err = world_error(world(5, 5, extra))
    assert err.path == "w.yaml" and err.line is not None and words in err.message, str(err)


def test_starts_are_at_most_8_and_headings_one_turn_either_way():
    starts = "start:\n" + "".join("  - {cell: [1, 1]}\n" for _ in range(9))
    assert "at most 8 robots" in world_error(world(5, 5, start=starts)).message
    err = world_error(world(5, 5, start="start: {cell: [1, 1], heading_deg: 1e308}"))
    assert "'heading_deg' must be -360 to 360 degrees" in err.message
    assert parse_maze(world(5, 5, start="start: {cell: [1, 1], heading_deg: -360}"), "w.yaml").starts


@pytest.mark.parametrize(
    "old, new, words",
    [
        (
            "wheel_diameter_mm: 56",
            "wheel_diameter_mm: 1e12",
            "'wheel_diameter_mm' must be 20 to 200 mm, got 1e+12",
        ),
        ("wheel_diameter_mm: 56", "wheel_diameter_mm: 19", "must be 20 to 200 mm"),
        ("axle_track_mm: 120", "axle_track_mm: 1e-9", "'axle_track_mm' must be 50 to 500 mm"),
        ("axle_track_mm: 120", "axle_track_mm: .nan", "must be a number"),
        ("width_cm: 15", "width_cm: 51", "'width_cm' must be 1 to 50 cm"),
        ("front_cm: 9", "front_cm: -51", "'front_cm' must be -50 to 50 cm"),
        (
            "radius_cm: 7, facing: down, spot_cm",
            "radius_cm: 32, facing: down, spot_cm",
            "must be 0 to 31.72 cm",
        ),
        (
            "spot_cm: 1.5",
            "spot_cm: 11",
            "'spot_cm' (diameter of the floor spot the sensor sees) must be 0.1 to 10",
        ),
        ("cone_deg: 15", "cone_deg: 181", "must be 1 to 180 degrees"),
        ("cone_deg: 15", "cone_deg: 15, aim_deg: 361", "'aim_deg' must be -360 to 360 degrees"),
        ("cone_deg: 15", "cone_deg: 15, max_cm: 1e6", "must be 1 to 1000 cm"),
        ("cone_deg: 15", "cone_deg: 15, noise: 101", "'noise' must be 0 to 100"),
        ("name: EV3 driving base", "name: " + "x" * 61, "at most 60"),
    ],
)
def test_robot_numbers_out_of_the_range_of_lego_parts_are_refused_with_it(old, new, words):
    assert old in BASE_ROBOT
    err = robot_error(BASE_ROBOT.replace(old, new, 1))
    assert err.line is not None and words in err.message, str(err)


def test_robot_numbers_at_the_ends_of_their_ranges_are_read():
    text = (
        BASE_ROBOT.replace("wheel_diameter_mm: 56", "wheel_diameter_mm: 200")
        .replace("axle_track_mm: 120", "axle_track_mm: 50")
        .replace("cone_deg: 15", "cone_deg: 180, max_cm: 1000, noise: 100, aim_deg: -360")
    )
    robot = parse_robot(text, "r.yaml")
    assert (robot.wheel_diameter_mm, robot.axle_track_mm) == (200, 50)


def test_more_motors_or_sensors_than_the_brick_has_ports_are_refused_before_each_is_read():
    sensors = "sensors:\n" + "".join(f"  - {{port: {n}, kind: nonsense}}\n" for n in range(5))
    text = BASE_ROBOT[: BASE_ROBOT.index("sensors:")] + sensors
    assert "'sensors' lists 5; the EV3 has 4" in robot_error(text).message


def test_an_arm_s_limits_are_within_100_turns():
    text = BASE_ROBOT.replace("motors:\n", "motors:\n  - {port: A, kind: medium, limits_deg: [-1e9, 0]}\n", 1)
    assert "within -36000 to 36000 degrees" in robot_error(text).message


def test_a_deep_mapping_from_the_page_is_refused_before_it_is_written_out():
    mapping: dict = {"name": "x"}
    for _ in range(2000):
        mapping = {"name": mapping}
    with pytest.raises(WorldFileError, match="nested more than 32 deep"):
        robot_mapping_text(mapping, "the page's robot")
    good = json.loads(json.dumps(__import__("yaml").safe_load(BASE_ROBOT)))
    assert parse_robot(robot_mapping_text(good), "p").name == "EV3 driving base"


def test_a_press_time_must_be_finite():
    for text in ("enter@nan", "enter@inf", "enter@1+nan"):
        with pytest.raises(ValueError, match="at most 86400 s"):
            parse_press(text)


def test_the_editor_s_edited_world_keeps_the_file_limits():
    source = MazeSource(world(5, 5), "w.yaml")
    data = {"cell_cm": 10, "cells": [[{"wall": False, "shade": 100, "color": None}] * 5] * 5, "regions": []}
    data["starts"] = [{"x_cm": 15, "y_cm": 15, "heading_deg": 1e300}]
    edited = edited_from_json(data)
    assert -180 <= edited.starts[0].heading_deg <= 180  # turned back into one turn
    for bad in ({"cell_cm": 0.001}, {"starts": [{"x_cm": 1e308, "y_cm": 15, "heading_deg": 0}]}):
        with pytest.raises(BadEdit):
            edited_from_json({**data, **bad})
    assert source.grid.width == 5
