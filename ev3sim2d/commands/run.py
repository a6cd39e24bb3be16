"""`ev3sim2d run`: run programs, one robot each, in a world; write the summary, trace and pictures."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ..grading.safe_text import one_line, printable
from ..render.outputs import add_picture_arguments, write_pictures
from ..results.summary import run_summary, write_summary
from ..simulator.bricks import become_subreaper
from ..simulator.program import ProgramError
from ..simulator.run import RunResult, echo_line, robot_names, run_programs, start_failure
from ..simulator.simulation import StartBlocked
from ..world.button_press import ButtonPress, parse_press
from ..world.maze_file import find_maze, load_maze
from ..world.robot_spec import RobotSpec, find_robot, load_robot, shipped_robot_names
from ..world.source_error import WorldFileError
from .debug_adapter import DebugAdapter
from .debug_prompt import DebugPrompt
from .exit_codes import EXIT_HUNG, EXIT_INTERRUPTED, EXIT_OK, EXIT_PROGRAM_ERROR, EXIT_USAGE, fail
from .plot import add_value_arguments, matplotlib_missing, value_names, write_plot
from .problem_lines import problem_lines

NAME = "run"
HELP = "run a program (or several, one robot each) in a world"


def add_programs_and_world(parser: argparse.ArgumentParser) -> None:
    """PROG... [-- ARG...], --maze and --robot, as `run` and `live` take them (PASSES_ARGUMENTS)."""
    parser.usage = "%(prog)s [options] PROG [PROG ...] [-- ARG ...]"
    parser.epilog = (
        "Arguments after -- are every program's own command line: `prog.py -- 26 1.5` gives "
        "sys.argv == ['prog.py', '26', '1.5'], as `python3 prog.py 26 1.5` does on a brick."
    )
    parser.add_argument("programs", nargs="+", metavar="PROG", help="python-ev3dev2 program file(s)")
    parser.add_argument(
        "--maze", default="empty", help="world file, or the name of a shipped world (default: empty)"
    )
    add_robot_option(parser, "program")


def add_robot_option(parser: argparse.ArgumentParser, each: str) -> None:
    """--robot: once for every robot, or once per program (`run`, `live`) or robot (`serve`)."""
    parser.add_argument(
        "--robot",
        action="append",
        default=[],
        metavar="FILE",
        help=f"robot file or shipped robot name: once for every robot, or once per {each} in order "
        "(default: the robot the start names, else the world's robot)",
    )


PASSES_ARGUMENTS = True  # `run PROG... -- ARG...`: what follows -- is the programs' own command line


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_programs_and_world(parser)
    add_run_options(
        parser, "stop a program that spins S real seconds without using the robot or the clock (default: 5)"
    )
    parser.add_argument(
        "--debug",
        action="store_true",
        help="stop at the program's first line in the debugger, a prompt here (breakpoint() in a program "
        "stops there too): the world waits while it is stopped; h at the prompt for help",
    )
    parser.add_argument(
        "--debug-adapter",
        type=int,
        metavar="PORT",
        help="debug from an editor instead: wait on 127.0.0.1:PORT (0: any free port) for one Debug Adapter "
        "Protocol client (VS Code's debugpy attach) that gives the token; docs/editors.md",
    )
    parser.add_argument(
        "--debug-token",
        metavar="TOKEN",
        help="the token the debugger must give (default: a new one, printed)",
    )


def add_run_options(parser: argparse.ArgumentParser, hang_help: str) -> None:
    """The options of a run and its outputs, as `run` and `serve` take them."""
    parser.add_argument(
        "--time",
        type=float,
        default=60.0,
        metavar="S",
        help="stop after S seconds of simulated time (default: 60)",
    )
    parser.add_argument(
        "--seed", type=int, default=0, help="seed for sensor noise and the program's random (default: 0)"
    )
    parser.add_argument("--png", metavar="FILE", help="write a picture of the end of the run")
    parser.add_argument("--summary", metavar="FILE", help="write a JSON summary of the run")
    parser.add_argument("--trace", metavar="FILE", help="write the full trace of the run (.npz)")
    add_plot_arguments(parser)
    parser.add_argument("--quiet", action="store_true", help="do not echo what the program prints")
    parser.add_argument(
        "--press",
        action="append",
        default=[],
        type=_press,
        metavar="BUTTON@S",
        help="press a brick button at S seconds (BUTTON@S+HOLD to hold it HOLD s; repeatable), e.g. enter@2.0",
    )
    parser.add_argument(
        "--hang-after",
        type=float,
        default=5.0,
        metavar="S",
        help=hang_help,
    )
    add_picture_arguments(parser)


def add_plot_arguments(parser: argparse.ArgumentParser) -> None:
    """--plot FILE and --plot-values NAMES: the chart of `ev3sim2d plot`, written at the end of the run."""
    parser.add_argument(
        "--plot",
        metavar="FILE",
        help="write a chart of the first robot's sensor values and motor speeds against time (PNG; "
        "needs matplotlib)",
    )
    add_value_arguments(parser, "--plot-values")


def _press(text: str) -> ButtonPress:
    try:
        return parse_press(text)
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err)) from None


class RobotOptionError(Exception):
    """A --robot option that cannot be used; the message says which and what to do."""


def robots_given(names: list[str], programs: list[str]) -> list[RobotSpec] | None:
    """The robots --robot gives: none (each start's or the world's robot), one for all, or one per program."""
    if len(names) > 1 and len(names) != len(programs):
        raise RobotOptionError(
            f"{len(names)} --robot options for {len(programs)} program(s); give --robot once (for every "
            f"robot) or once per program, in the programs' order"
        )
    robots = []
    for number, (name, program) in enumerate(zip(names, programs, strict=False), start=1):
        found = find_robot(name)
        if found is None:
            which = f"--robot {name}"
            if len(names) > 1:
                which += f" (the robot of the {_ordinal(number)} program, {program})"
            raise RobotOptionError(
                f"{which}: no such robot file (looked in the current folder and among the shipped robots: "
                f"{', '.join(shipped_robot_names())}); check the path, or give a shipped robot's name"
            )
        robots.append(load_robot(found))
    return robots or None


def _ordinal(number: int) -> str:
    suffix = "th" if 10 <= number % 100 <= 20 else {1: "st", 2: "nd", 3: "rd"}.get(number % 10, "th")
    return f"{number}{suffix}"


def write_outputs(args, result: RunResult, programs: list[str]) -> None:
    """The outputs the options ask for: trace, summary, pictures and video."""
    if args.trace:
        result.trace.save(args.trace)
    if args.summary:
        write_summary(run_summary(result, programs, args.maze, args.seed, args.time), args.summary)
    if args.png or args.video or args.frames:
        write_pictures(result.trace, args)
    if args.plot:
        write_plot(result.trace, args.plot, value_names(args.plot_values))


ATTACH_S = 120  # seconds to wait for the editor's debugger to attach

STATUS_CODES = {
    "finished": EXIT_OK,
    "time_limit": EXIT_OK,
    "error": EXIT_PROGRAM_ERROR,
    "hung": EXIT_HUNG,
    "interrupted": EXIT_INTERRUPTED,
    "crashed": EXIT_PROGRAM_ERROR,
}


def report_end(args, result: RunResult, programs: list[str]) -> int:
    """Show the program's error, write the outputs, say how the run ended; the exit status.  What the program
    chose (its error's text, its traceback, the reason that quotes them) reaches the terminal escaped."""
    unstartable = start_failure(result)
    if unstartable is not None:  # its brick could not compile it: said as Python says it, with the line
        code = fail(printable(unstartable), EXIT_PROGRAM_ERROR)
        for line in problem_lines(result):
            print(line, file=sys.stderr)
        return code
    if result.error:
        print(printable(result.error["traceback"].rstrip()), file=sys.stderr)
        if result.error.get("hint"):
            print(f"hint: {printable(result.error['hint'])}", file=sys.stderr)
    for line in problem_lines(result):  # (an editor's problem matcher reads these: problem_lines.py)
        print(line, file=sys.stderr)
    try:
        write_outputs(args, result, programs)
    except OSError as err:
        print(f"ev3sim2d: error: could not write the outputs: {err}", file=sys.stderr)
        return EXIT_USAGE
    for note in result.notes:
        print(f"ev3sim2d: note: {printable(note)}", file=sys.stderr)
    speed = result.sim_time_s / result.wall_time_s if result.wall_time_s > 0 else float("inf")
    print(
        f"ev3sim2d: {one_line(result.reason)} (simulated in {result.wall_time_s:.2f} s, {speed:.0f}x real time)",
        file=sys.stderr,
    )
    return STATUS_CODES[result.status]


def main(args) -> int:
    if args.time is not None and args.time <= 0:
        return fail("--time must be a positive number of seconds")
    if args.plot and (hint := matplotlib_missing()) is not None:
        return fail(f"--plot: {hint}")
    try:
        world = load_maze(find_maze(args.maze))
        robot = robots_given(args.robot, args.programs)
        for program in args.programs:
            if not Path(program).is_file():
                return fail(f"{program}: no such program file")
        echo = None if args.quiet else echo_line(sys.stdout, len(args.programs), show=one_line)
        debugger = DebugPrompt(robot_names(len(args.programs)))
        if args.debug_adapter is not None:
            debugger = DebugAdapter(args.debug_adapter, args.debug_token)
            if not debugger.attach(timeout_s=ATTACH_S):
                return fail(f"no debugger attached within {ATTACH_S} s, or it did not give the run's token")
        become_subreaper()  # whatever a program's process leaves behind comes back here and is ended
        result = run_programs(
            args.programs,
            world,
            robot,
            args.time,
            args.seed,
            args.hang_after,
            echo,
            presses=args.press,
            arguments=getattr(args, "program_arguments", ()),
            debug="start" if args.debug or args.debug_adapter is not None else "breakpoints",
            debugger=debugger,
            keep_written=True,  # (a DataLog's CSV, a log: beside the program afterwards, as on a brick)
        )
    except (WorldFileError, RobotOptionError) as err:
        return fail(str(err))
    except ProgramError as err:  # a syntax error shows the program's line: what it holds is the program's
        return fail(printable(str(err)), EXIT_PROGRAM_ERROR)
    except (StartBlocked, FileNotFoundError) as err:
        return fail(str(err))

    status = report_end(args, result, args.programs)
    if isinstance(debugger, DebugAdapter):
        debugger.finished(status)
    return status
