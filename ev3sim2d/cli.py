"""The `ev3sim2d` command: run programs in worlds, list the shipped worlds."""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from .program import ProgramError
from .run import RunResult, echo_line, run_programs
from .simulation import StartBlocked
from .summary import run_summary, write_summary
from .world.maze_file import find_maze, list_shipped_mazes, load_maze
from .world.robot_spec import load_robot
from .world.source_error import WorldFileError

EXIT_OK, EXIT_PROGRAM_ERROR, EXIT_USAGE, EXIT_HUNG, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ev3sim2d",
        description="Run unmodified python-ev3dev2 programs on a simulated EV3 robot in a 2D grid world.",
    )
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="run a program (or several, one robot each) in a world")
    run.add_argument("programs", nargs="+", metavar="PROG", help="python-ev3dev2 program file(s)")
    run.add_argument(
        "--maze", default="empty", help="world file, or the name of a shipped world (default: empty)"
    )
    run.add_argument("--robot", metavar="FILE", help="robot description file (default: the world's robot)")
    run.add_argument(
        "--time",
        type=float,
        default=60.0,
        metavar="S",
        help="stop after S seconds of simulated time (default: 60)",
    )
    run.add_argument(
        "--seed", type=int, default=0, help="seed for sensor noise and the program's random (default: 0)"
    )
    run.add_argument("--png", metavar="FILE", help="write a picture of the end of the run")
    run.add_argument("--summary", metavar="FILE", help="write a JSON summary of the run")
    run.add_argument("--trace", metavar="FILE", help="write the full trace of the run (.npz)")
    run.add_argument("--quiet", action="store_true", help="do not echo what the program prints")
    run.add_argument(
        "--hang-after",
        type=float,
        default=5.0,
        metavar="S",
        help="stop a program that spins S real seconds without using the robot or the clock (default: 5)",
    )

    sub.add_parser("mazes", help="list the shipped worlds")
    return parser


def _fail(message: str, code: int = EXIT_USAGE) -> int:
    print(f"ev3sim2d: error: {message}", file=sys.stderr)
    return code


def _cmd_mazes() -> int:
    for name, title in list_shipped_mazes():
        print(f"{name:12} {title}")
    return EXIT_OK


def _write_outputs(args, result: RunResult) -> None:
    if args.trace:
        result.trace.save(args.trace)
    if args.summary:
        write_summary(run_summary(result, args.programs, args.maze, args.seed, args.time), args.summary)
    if args.png:
        from .render.frame import write_png

        write_png(result.trace, args.png)


def _cmd_run(args) -> int:
    if args.time is not None and args.time <= 0:
        return _fail("--time must be a positive number of seconds")
    try:
        world = load_maze(find_maze(args.maze))
        robot = load_robot(args.robot) if args.robot else None
        for program in args.programs:
            if not Path(program).is_file():
                return _fail(f"{program}: no such program file")
        echo = None if args.quiet else echo_line(sys.stdout, len(args.programs))
        result = run_programs(args.programs, world, robot, args.time, args.seed, args.hang_after, echo)
    except WorldFileError as err:
        return _fail(str(err))
    except ProgramError as err:
        return _fail(str(err), EXIT_PROGRAM_ERROR)
    except (StartBlocked, FileNotFoundError) as err:
        return _fail(str(err))

    if result.error:
        print(result.error["traceback"].rstrip(), file=sys.stderr)
        if result.error.get("hint"):
            print(f"hint: {result.error['hint']}", file=sys.stderr)
    try:
        _write_outputs(args, result)
    except OSError as err:
        print(f"ev3sim2d: error: could not write the outputs: {err}", file=sys.stderr)
        return EXIT_USAGE
    speed = result.sim_time_s / result.wall_time_s if result.wall_time_s > 0 else float("inf")
    print(
        f"ev3sim2d: {result.reason} (simulated in {result.wall_time_s:.2f} s, {speed:.0f}x real time)",
        file=sys.stderr,
    )
    code = {
        "finished": EXIT_OK,
        "time_limit": EXIT_OK,
        "error": EXIT_PROGRAM_ERROR,
        "hung": EXIT_HUNG,
        "interrupted": EXIT_INTERRUPTED,
    }[result.status]
    if any(not t.done for t in result.tasks):  # a program thread that would not stop
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    return code


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.command == "mazes":
        return _cmd_mazes()
    return _cmd_run(args)


if __name__ == "__main__":
    sys.exit(main())
