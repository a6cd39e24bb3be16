"""`ev3sim2d show`: draw a world file with the robot at its start, for previews and documentation."""

from __future__ import annotations

import argparse

from ..simulator.simulation import Simulation, StartBlocked
from ..world.maze_file import find_maze, load_maze
from ..world.robot_spec import load_robot
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_OK, fail

NAME = "show"
HELP = "draw a world (a maze file or a shipped world's name) with the robot at its start"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("maze", metavar="MAZE", help="world file, or the name of a shipped world")
    parser.add_argument("--png", metavar="FILE", required=True, help="the picture to write")
    parser.add_argument("--robot", metavar="FILE", help="robot description file (default: the world's robot)")
    parser.add_argument(
        "--width", type=int, default=800, metavar="PX", help="picture width in pixels (default: 800)"
    )


def main(args) -> int:
    if not 160 <= args.width <= 8000:
        return fail("--width must be 160 to 8000 pixels")
    try:
        world = load_maze(find_maze(args.maze))
        given = load_robot(args.robot) if args.robot else None
        names = ["robot"] if len(world.starts) == 1 else [f"robot{i + 1}" for i in range(len(world.starts))]
        # a simulation that never ticks: its trace describes the world and the robots at their starts
        robots = [(names[i], given or world.start_robot(i), pose) for i, pose in enumerate(world.starts)]
        trace = Simulation(world, robots).trace
    except WorldFileError as err:
        return fail(str(err))
    except (StartBlocked, FileNotFoundError) as err:
        return fail(str(err))
    from ..render.frame import draw_world_picture, save_png  # (OpenCV: only when a picture is drawn)

    try:
        save_png(draw_world_picture(trace, args.width), args.png)
    except OSError as err:
        return fail(str(err))
    return EXIT_OK
