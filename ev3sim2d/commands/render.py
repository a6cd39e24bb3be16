"""`ev3sim2d render`: draw a saved trace again (video, frames, picture) without running the program."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..render.outputs import add_picture_arguments, write_pictures
from ..results.trace import Trace
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_OK, fail

NAME = "render"
HELP = "draw a saved trace (from `run --trace`) as a video, frames or a picture"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("trace", metavar="TRACE", help="a trace file written by `ev3sim2d run --trace`")
    parser.add_argument("--png", metavar="FILE", help="write a picture of the end of the run")
    add_picture_arguments(parser)


def main(args) -> int:
    if not (args.png or args.video or args.frames):
        return fail("nothing to draw: give --video FILE, --png FILE or --frames DIR")
    if not Path(args.trace).is_file():
        return fail(f"{args.trace}: no such trace file")
    try:
        trace = Trace.load(args.trace)
    except (ValueError, KeyError, OSError) as err:
        return fail(
            f"{args.trace}: cannot read it as a trace ({err}); write one with `ev3sim2d run ... --trace FILE`"
        )
    try:
        write_pictures(trace, args)
    except WorldFileError as err:
        return fail(f"{args.trace}: the world in the trace does not read: {err}")
    except OSError as err:
        return fail(f"could not write the pictures: {err}")
    return EXIT_OK
