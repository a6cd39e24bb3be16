"""`ev3sim2d join`: run a program here, on a robot of a world another computer serves (docs/network.md)."""

from __future__ import annotations

import argparse
import sys

from ..grading.safe_text import one_line, printable
from ..join import JoinError, parse_address, run_joined
from ..simulator.bricks import become_subreaper
from ..simulator.program import ProgramError
from .exit_codes import EXIT_INTERRUPTED, EXIT_PROGRAM_ERROR, EXIT_USAGE, fail
from .run import STATUS_CODES

NAME = "join"
HELP = "run a program here, on a robot of a world that `ev3sim2d serve` holds"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("address", metavar="HOST:PORT", help="where the world is served, e.g. 127.0.0.1:9003")
    parser.add_argument("program", metavar="PROG", help="python-ev3dev2 program file")
    parser.add_argument("--robot", type=int, metavar="K", help="which robot (1, 2, ...; default: a free one)")
    parser.add_argument("--name", help="your name, as the world shows it (default: the program's name)")
    parser.add_argument("--token", help="the join token `ev3sim2d serve` printed (needed off this computer)")
    parser.add_argument(
        "--wait",
        type=float,
        default=0.0,
        metavar="S",
        help="keep trying to connect for S seconds while no world is served there yet (default: 0)",
    )
    parser.add_argument("--quiet", action="store_true", help="do not show what the program prints")


def _log(text: str) -> None:
    """A line for the terminal; what the program (or the world) chose in it, escaped."""
    print(f"ev3sim2d: {one_line(text)}", file=sys.stderr, flush=True)


def _echo(t_s: float, stream: str, text: str) -> None:
    """A line the program printed, its control characters shown escaped (safe_text.py)."""
    out = sys.stderr if stream == "stderr" else sys.stdout
    out.write(f"[{float(t_s):8.3f} s] {one_line(str(text))}\n")
    out.flush()


def main(args) -> int:
    try:
        parse_address(args.address)
    except ValueError as err:
        return fail(str(err))
    if args.robot is not None and args.robot < 1:
        return fail(f"--robot {args.robot}: robots are numbered from 1")
    become_subreaper()
    try:
        result = run_joined(
            args.address,
            args.program,
            args.robot,
            args.name,
            args.token,
            None if args.quiet else _echo,
            _log,
            args.wait,
        )
    except ProgramError as err:
        return fail(printable(str(err)), EXIT_PROGRAM_ERROR)
    except JoinError as err:
        return fail(one_line(str(err)))
    except KeyboardInterrupt:
        return fail("interrupted: this robot's program was stopped", EXIT_INTERRUPTED)
    error = (result.local_end or {}).get("error")
    if isinstance(error, dict) and error.get("traceback"):
        print(printable(str(error["traceback"]).rstrip()), file=sys.stderr)
    if result.over is None:
        return fail(one_line(f"{result.lost or 'the world went away'} before the run was over"), EXIT_USAGE)
    own = result.over.get("robot") or {}
    _log(f"robot {result.seat['number']}: {own.get('reason', '?')}")
    _log(f"the run: {result.over.get('reason', '?')}")
    return STATUS_CODES.get(own.get("status"), EXIT_PROGRAM_ERROR)
