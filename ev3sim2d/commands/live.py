"""`ev3sim2d live`: watch programs drive in the browser; pause, step, reload, drag robots, edit the world."""

from __future__ import annotations

import argparse
import threading
import webbrowser
from pathlib import Path

from ..live.engine import MAX_SPEED, MIN_SPEED, LiveError, LiveRun
from ..live.server import LiveServer, LiveWorldFile
from ..simulator.bricks import become_subreaper
from ..simulator.program import ProgramError
from ..simulator.run import robot_names
from ..world.maze_file import find_maze, load_maze
from ..world.source_error import WorldFileError
from .debug_prompt import DebugPrompt
from .exit_codes import EXIT_OK, fail
from .run import RobotOptionError, add_programs_and_world, robots_given

NAME = "live"
HELP = "run programs live in the browser: pause, step, reload, drag the robot, edit the world, plot values"


PASSES_ARGUMENTS = True  # `live PROG... -- ARG...`: what follows -- is the programs' own command line


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_programs_and_world(parser)
    parser.add_argument("--port", type=int, default=0, help="port on 127.0.0.1 (default: a free one)")
    parser.add_argument(
        "--debug",
        action="store_true",
        help="stop at the program's first line in the debugger, a prompt in this terminal (breakpoint() "
        "stops there too); the page says where it is stopped, and the world waits",
    )
    pace = parser.add_mutually_exclusive_group()
    pace.add_argument(
        "--speed",
        type=float,
        default=1.0,
        metavar="X",
        help=f"times real time, {MIN_SPEED:g} to {MAX_SPEED:g} (default: 1); the page can change it",
    )
    pace.add_argument("--max-speed", action="store_true", help="run as fast as the computer can")
    parser.add_argument(
        "--time", type=float, default=None, metavar="S", help="end the run at S seconds (default: no limit)"
    )
    parser.add_argument(
        "--seed", type=int, default=0, help="seed for sensor noise and the program's random (default: 0)"
    )
    parser.add_argument(
        "--no-browser", action="store_true", help="only print the address; do not open a browser"
    )
    parser.add_argument(
        "--trace", metavar="FILE", help="when you stop (Ctrl+C), write the last run's trace (.npz)"
    )


def main(args) -> int:
    if not 0 <= args.port <= 65535:
        return fail("--port must be 0 to 65535")
    speed = None if args.max_speed else args.speed
    if speed is not None and not MIN_SPEED <= speed <= MAX_SPEED:
        return fail(f"--speed is {MIN_SPEED:g} to {MAX_SPEED:g} times real time; or --max-speed")
    try:
        maze_path = find_maze(args.maze)
        world = load_maze(maze_path)
        robots = robots_given(args.robot, args.programs)
        live = LiveRun(
            args.programs,
            world,
            robots,
            speed=speed,
            seed=args.seed,
            time_limit_s=args.time,
            arguments=getattr(args, "program_arguments", ()),
            debug="start" if args.debug else "breakpoints",
            debugger=DebugPrompt(robot_names(len(args.programs))),
        )
    except (WorldFileError, ProgramError, RobotOptionError, LiveError, FileNotFoundError) as err:
        return fail(str(err))
    own_file = Path(args.maze).is_file()
    world_file = LiveWorldFile(maze_path if own_file else None, None if own_file else maze_path.stem)
    try:
        server = LiveServer(live, world_file, args.port)
    except OSError as err:
        return fail(f"cannot listen on 127.0.0.1:{args.port}: {err.strerror}")
    become_subreaper()  # whatever a program's process leaves behind comes back here and is ended
    live.start()
    print(f"ev3sim2d live: {', '.join(args.programs)} at {server.url} (Ctrl+C to stop)", flush=True)
    print(
        "ev3sim2d live: the address's #token=... is this start's key; only a page opened with it can read or "
        "change anything, so keep it to yourself (docs/live.md)",
        flush=True,
    )
    if not args.no_browser:
        threading.Thread(target=webbrowser.open, args=(server.url,), daemon=True).start()
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        print("ev3sim2d live: stopped", flush=True)
    finally:
        server.server_close()
        trace = live.close()
    if args.trace:
        if trace is None:
            print("ev3sim2d live: no run ended, so there is no trace to write", flush=True)
        else:
            trace.save(args.trace)
            print(f"ev3sim2d live: the last run's trace is in {args.trace}", flush=True)
    return EXIT_OK
