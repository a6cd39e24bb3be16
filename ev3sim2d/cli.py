"""The `ev3sim2d` command: one subcommand per module in ev3sim2d/commands/."""

from __future__ import annotations

import argparse
import sys

from .commands import edit, grade, mazes, render, run, show

COMMANDS = [run, mazes, grade, render, show, edit]  # a new subcommand: a module in commands/, one entry here


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ev3sim2d",
        description="Run unmodified python-ev3dev2 programs on a simulated EV3 robot in a 2D grid world.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS:
        command.add_arguments(sub.add_parser(command.NAME, help=command.HELP, description=command.HELP))
    return parser


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    command = next(c for c in COMMANDS if c.NAME == args.command)
    return command.main(args)


if __name__ == "__main__":
    sys.exit(main())
