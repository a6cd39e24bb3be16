"""`ev3sim2d serve`: hold a world for N robots; programs join it from other computers (docs/network.md)."""

from __future__ import annotations

import argparse
import secrets
import sys

from ..grading.safe_text import one_line
from ..serve import serve_run
from ..simulator.bricks import become_subreaper
from ..simulator.lobby import AddressInUse, Lobby, is_loopback
from ..simulator.program import ProgramError
from ..simulator.run import echo_line
from ..simulator.simulation import StartBlocked
from ..world.maze_file import find_maze, load_maze
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_INTERRUPTED, fail
from .plot import matplotlib_missing
from .run import RobotOptionError, add_robot_option, add_run_options, report_end, robots_given

NAME = "serve"
HELP = "hold a world for N robots whose programs join over the network (ev3sim2d join)"
DEFAULT_PORT = 9003


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--maze", required=True, help="world file, or the name of a shipped world")
    parser.add_argument(
        "--robots", type=int, metavar="N", help="how many robots (default: one per start of the world)"
    )
    parser.add_argument(
        "--host",
        default="127.0.0.1",
        help="the address to listen on (default: 127.0.0.1, this computer only); any other needs a join "
        "token, which is printed",
    )
    parser.add_argument("--port", type=int, default=DEFAULT_PORT, help=f"TCP port (default: {DEFAULT_PORT})")
    parser.add_argument("--token", help="the join token (default: a random one, when --host is not loopback)")
    add_robot_option(parser, "robot")
    add_run_options(
        parser, "drop a brick that is silent S real seconds while the world waits for it (default: 5)"
    )


def _log(text: str) -> None:
    """A line for the terminal; what a joiner or its program chose (a name, an error) in it, escaped."""
    print(f"ev3sim2d: {one_line(text)}", file=sys.stderr, flush=True)


def main(args) -> int:
    if args.time is not None and args.time <= 0:
        return fail("--time must be a positive number of seconds")
    if args.plot and (hint := matplotlib_missing()) is not None:
        return fail(f"--plot: {hint}")
    if not 0 <= args.port < 65536:
        return fail(f"--port {args.port}: a TCP port is 1 to 65535")
    try:
        world = load_maze(find_maze(args.maze))
        count = len(world.starts) if args.robots is None else args.robots
        if not 1 <= count <= len(world.starts):
            return fail(
                f"--robots {count}: the world '{world.name}' has {len(world.starts)} start pose(s); "
                f"serve 1 to {len(world.starts)} robots, or add starts to the world file"
            )
        robot = robots_given(args.robot, [f"robot {i + 1}" for i in range(count)])
    except (WorldFileError, RobotOptionError, FileNotFoundError) as err:
        return fail(str(err))
    token = args.token
    if token is None and not is_loopback(args.host):
        token = secrets.token_urlsafe(6)
    lobby = Lobby(args.host, args.port, count, token, _log)
    try:
        host, port = lobby.open()
    except AddressInUse as err:
        return fail(str(err))
    except OSError as err:
        return fail(f"cannot listen on {args.host}:{args.port}: {err.strerror or err}")
    where = f"[{host}]:{port}" if ":" in host else f"{host}:{port}"
    _log(f"serving '{world.name}' for {count} robot(s) on {where}")
    join = f"ev3sim2d join {where} PROGRAM.py [--robot 1..{count}]" + (f" --token {token}" if token else "")
    _log(f"join with: {join}")
    if host in ("0.0.0.0", "::"):
        _log("(from another computer, put this computer's address on the network in place of the host)")
    names = {}
    echo = None if args.quiet else echo_line(sys.stdout, count, show=one_line)
    become_subreaper()
    try:
        result, guests = serve_run(
            lobby, world, count, robot, args.time, args.seed, args.hang_after, echo, args.press
        )
        names = [f"{g.fields['name']}: {g.fields['program']}" for g in guests]
    except KeyboardInterrupt:
        joined = sum(1 for g in lobby.guests if g.greeting is not None)
        return fail(
            f"interrupted before the run: {joined} of {count} robot(s) had a program", EXIT_INTERRUPTED
        )
    except (ProgramError, StartBlocked) as err:
        return fail(one_line(str(err)))
    finally:
        lobby.close()
    for own, name in zip(result.robots, names, strict=False):
        _log(f"{own['robot']} ({name}): {own['reason']}")
    return report_end(args, result, names)
