"""`ev3sim2d mazes`: list the shipped worlds."""

from __future__ import annotations

import argparse

from ..world.maze_file import list_shipped_mazes
from .exit_codes import EXIT_OK

NAME = "mazes"
HELP = "list the shipped worlds"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    pass


def main(args) -> int:
    for name, title in list_shipped_mazes():
        print(f"{name:12} {title}")
    return EXIT_OK
