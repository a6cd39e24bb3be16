"""Several robots in one world, each with its own robot file (issue 13).

A robot file comes from `--robot` (once for all, or once per program), else from the start pose it
starts at (`start: [{..., robot: FILE}]`), else from the world's `robot:`; and every shipped world
with several starts runs one program per start.
"""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ev3sim2d.results.trace import Trace
from ev3sim2d.simulator.run import robot_specs, run_programs
from ev3sim2d.world.maze_file import find_maze, list_shipped_mazes, load_maze, parse_maze
from ev3sim2d.world.robot_spec import default_robot, load_robot, shipped_robots_dir
from ev3sim2d.world.source_error import WorldFileError

ROOT = Path(__file__).resolve().parents[1]
BASE_TEXT = (shipped_robots_dir() / "ev3-driving-base.yaml").read_text()
ONE_TURN = "from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C\nMoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(30, 30, 1)\n"
TRIVIAL = "from ev3dev2.motor import *\nMoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)\n"
GRID = """grid: |
  ####################
  #..................#
  #..................#
  #..................#
  #..................#
  #..................#
  ####################
"""


def robot_file(
    folder: Path, name: str, wheel_mm: int = 56, color: str = "[230, 170, 30]", axle_mm=120
) -> Path:
    """The driving base with another wheel diameter, axle track and colour."""
    text = BASE_TEXT.replace("wheel_diameter_mm: 56", f"wheel_diameter_mm: {wheel_mm}")
    text = text.replace("axle_track_mm: 120", f"axle_track_mm: {axle_mm}")
    assert f"wheel_diameter_mm: {wheel_mm}" in text and f"axle_track_mm: {axle_mm}" in text
    lines = [line for line in text.splitlines() if not line.startswith("color:")]
    path = folder / f"{name}.yaml"
    path.write_text("\n".join(lines) + f"\ncolor: {color}\n")
    return path


def two_lanes(folder: Path, first: str = "", second: str = "", world_robot: str = "") -> Path:
    """A world file with two starts 30 cm apart, both facing +x; `first`/`second` add keys to a start."""
    text = (
        "title: two lanes\ncell_cm: 10\n"
        + GRID
        + "start:\n"
        + f"  - {{x_cm: 40, y_cm: 20, heading_deg: 0{first}}}\n"
        + f"  - {{x_cm: 40, y_cm: 50, heading_deg: 0{second}}}\n"
        + world_robot
    )
    path = folder / "lanes.yaml"
    path.write_text(text)
    return path


def driven_cm(trace: Trace, robot: int) -> float:
    poses = trace.poses(robot)
    return float(math.hypot(poses[-1][0] - poses[0][0], poses[-1][1] - poses[0][1]))


def program(folder: Path, text: str = ONE_TURN, name: str = "drive.py") -> Path:
    path = folder / name
    path.write_text(text)
    return path


def cli(*args, cwd=ROOT):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=120,
    )


# -- each program on its own robot ------------------------------------------------------------


def test_two_programs_run_with_their_own_robot_files(tmp_path):
    small = load_robot(robot_file(tmp_path, "small", wheel_mm=43, color="blue"))
    world = load_maze(two_lanes(tmp_path))
    drive = program(tmp_path)
    result = run_programs([drive, drive], world, [default_robot(), small], time_limit_s=10)
    assert result.status == "finished", result.reason
    first, second = result.trace.robots
    assert first["wheel_diameter_mm"] == 56 and second["wheel_diameter_mm"] == 43
    assert first["color"] != second["color"]
    # one turn of the wheels drives one wheel circumference: as far as each robot's own wheels say
    assert driven_cm(result.trace, 0) == pytest.approx(math.pi * 5.6, abs=0.2)
    assert driven_cm(result.trace, 1) == pytest.approx(math.pi * 4.3, abs=0.2)


def test_one_robot_given_drives_every_program_as_before(tmp_path):
    small = load_robot(robot_file(tmp_path, "small", wheel_mm=43))
    world = load_maze(two_lanes(tmp_path))
    drive = program(tmp_path)
    for given in (small, [small]):
        result = run_programs([drive, drive], world, given, time_limit_s=10)
        assert [r["wheel_diameter_mm"] for r in result.trace.robots] == [43, 43]


def test_a_start_that_names_a_robot_file_gets_that_robot(tmp_path):
    robot_file(tmp_path, "small", wheel_mm=43, color="green")
    world = load_maze(two_lanes(tmp_path, second=", robot: small.yaml"))  # found next to the world file
    assert world.start_robot(0) == world.robot == default_robot()
    assert world.start_robot(1).wheel_diameter_mm == 43
    drive = program(tmp_path)
    result = run_programs([drive, drive], world, time_limit_s=10)  # every existing caller: no robot given
    assert result.status == "finished", result.reason
    assert [r["wheel_diameter_mm"] for r in result.trace.robots] == [56, 43]
    assert driven_cm(result.trace, 1) == pytest.approx(math.pi * 4.3, abs=0.2)


def test_a_start_may_name_a_shipped_robot_or_write_one_inline(tmp_path):
    robot_file(tmp_path, "wide", axle_mm=150)
    inline = "{name: tiny, wheel_diameter_mm: 30, axle_track_mm: 80, body: {front_cm: 5, back_cm: 5, width_cm: 10}, motors: [{port: B, wheel: left}, {port: C, wheel: right}]}"
    world = load_maze(
        two_lanes(
            tmp_path,
            first=", robot: ev3-driving-base",
            second=f", robot: {inline}",
            world_robot="robot: wide.yaml\n",
        )
    )
    assert world.robot.axle_track_mm == 150
    assert world.start_robot(0) == default_robot()
    assert world.start_robot(1).name == "tiny" and world.start_robot(1).wheel_diameter_mm == 30


def test_the_command_line_comes_first_then_the_start_then_the_world(tmp_path):
    robot_file(tmp_path, "start-robot", wheel_mm=43)
    robot_file(tmp_path, "world-robot", wheel_mm=62)
    world = load_maze(
        two_lanes(tmp_path, first=", robot: start-robot.yaml", world_robot="robot: world-robot.yaml\n")
    )
    given = load_robot(robot_file(tmp_path, "given", wheel_mm=50))

    def wheels(robot):
        return [spec.wheel_diameter_mm for spec in robot_specs(world, 2, robot)]

    assert wheels(None) == [43, 62]  # start 1 names its robot; start 2 has the world's
    assert wheels(given) == [50, 50]  # --robot once: every robot
    assert wheels([given]) == [50, 50]
    assert wheels([None, given]) == [43, 50]  # one per program: None is "not given"
    assert wheels([given, None]) == [50, 62]


def test_the_command_line_gives_each_program_its_robot_in_order(tmp_path):
    small = robot_file(tmp_path, "small", wheel_mm=43, color="blue")
    world = two_lanes(tmp_path)
    drive = program(tmp_path)
    trace = tmp_path / "run.npz"
    result = cli(
        "run",
        drive,
        drive,
        "--maze",
        world,
        "--robot",
        small,
        "--robot",
        "ev3-driving-base",
        "--quiet",
        "--trace",
        trace,
    )
    assert result.returncode == 0, result.stderr
    robots = Trace.load(trace).robots
    assert [r["wheel_diameter_mm"] for r in robots] == [43, 56]
    result = cli("run", drive, drive, "--maze", world, "--robot", small, "--quiet", "--trace", trace)
    assert result.returncode == 0, result.stderr
    assert [r["wheel_diameter_mm"] for r in Trace.load(trace).robots] == [43, 43]


# -- mistakes ----------------------------------------------------------------------------------


def test_more_robots_than_programs_is_refused_with_the_fix(tmp_path):
    drive = program(tmp_path)
    world = two_lanes(tmp_path)
    base = "ev3-driving-base"
    result = cli("run", drive, drive, "--maze", world, "--robot", base, "--robot", base, "--robot", base)
    assert result.returncode == 2
    assert "3 --robot options for 2 program(s)" in result.stderr
    assert "give --robot once (for every robot) or once per program" in result.stderr
    with pytest.raises(ValueError, match="3 robots for 2 programs"):
        robot_specs(load_maze(world), 2, [default_robot()] * 3)


def test_a_missing_robot_file_on_the_command_line_is_named(tmp_path):
    drive = program(tmp_path)
    world = two_lanes(tmp_path)
    result = cli("run", drive, "--maze", world, "--robot", "nope.yaml")
    assert result.returncode == 2
    assert "--robot nope.yaml: no such robot file" in result.stderr
    assert "shipped robots: ev3-driving-base" in result.stderr
    other = program(tmp_path, name="second.py")
    result = cli("run", drive, other, "--maze", world, "--robot", "ev3-driving-base", "--robot", "nope.yaml")
    assert result.returncode == 2
    assert (
        "--robot nope.yaml (the robot of the 2nd program, " in result.stderr and "second.py)" in result.stderr
    )


def test_a_broken_robot_file_on_the_command_line_says_where(tmp_path):
    broken = tmp_path / "broken.yaml"
    broken.write_text(BASE_TEXT.replace("wheel_diameter_mm: 56", "wheel_diameter_mm: -3"))
    result = cli("run", program(tmp_path), "--maze", two_lanes(tmp_path), "--robot", broken)
    assert result.returncode == 2
    assert "broken.yaml:" in result.stderr and "wheel_diameter_mm" in result.stderr


def test_a_start_naming_a_missing_robot_file_points_at_it(tmp_path):
    path = two_lanes(tmp_path, second=", robot: nope.yaml")
    with pytest.raises(WorldFileError) as caught:
        load_maze(path)
    message = str(caught.value)
    assert message.startswith(f"{path}:13:")  # the line of the second start
    assert "no robot file 'nope.yaml'" in message and "looked next to the maze file" in message


def test_a_start_robot_that_is_not_a_file_name_or_mapping_is_refused():
    text = "title: t\n" + GRID + "start:\n  - {x_cm: 40, y_cm: 20, robot: [1, 2]}\n"
    with pytest.raises(WorldFileError, match="'robot' must be a robot file name or a mapping"):
        parse_maze(text, "<test>")


# -- shipped worlds for several robots ---------------------------------------------------------

MULTI = [name for name, _ in list_shipped_mazes() if len(load_maze(find_maze(name)).starts) > 1]


def test_the_worlds_for_several_robots_are_shipped():
    assert {"sumo", "sumo-4", "line-shared", "maze-race"} <= set(MULTI)
    starts = {name: len(load_maze(find_maze(name)).starts) for name in MULTI}
    assert starts["sumo"] == 2 and starts["sumo-4"] == 4 and starts["line-shared"] == 2
    assert starts["maze-race"] == 4
    for name, region in (
        ("sumo", "ring"),
        ("sumo-4", "ring"),
        ("maze-race", "goal"),
        ("line-shared", "start2"),
    ):
        world = load_maze(find_maze(name))
        assert world.region(region)
        if region == "ring":
            assert all(world.region("ring").contains(p.x_cm, p.y_cm) for p in world.starts)


@pytest.mark.parametrize("name", MULTI)
def test_a_shipped_world_for_several_robots_runs_one_program_per_start(name, tmp_path):
    world = load_maze(find_maze(name))
    drive = program(tmp_path, TRIVIAL)
    count = len(world.starts)
    result = run_programs([drive] * count, world, time_limit_s=5)  # a blocked start raises StartBlocked
    assert result.status == "finished", result.reason
    assert len(result.trace.robots) == count
    for robot in range(count):
        assert driven_cm(result.trace, robot) > 5, f"robot {robot + 1} did not move"
        first_tick = result.trace.motion()[0, result.trace.robot_columns(robot)]
        assert first_tick[3] == 0, f"robot {robot + 1} starts touching a wall or a robot"
        assert not np.isnan(result.trace.poses(robot)).any()
