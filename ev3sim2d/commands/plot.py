"""`ev3sim2d plot`: a saved trace's sensor readings and motor speeds against time, as a PNG chart."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..results.output_files import write_file
from ..results.trace import Trace
from .exit_codes import EXIT_OK, fail

NAME = "plot"
HELP = "draw sensor values and motor speeds of a saved trace (from `run --trace`) against time, as PNG"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("trace", metavar="TRACE", help="a trace file written by `ev3sim2d run --trace`")
    parser.add_argument("--png", metavar="FILE", help="write the chart to FILE (PNG)")
    add_value_arguments(parser, "--values")
    parser.add_argument(
        "--robot",
        type=int,
        default=1,
        metavar="N",
        help="whose values: the robot of the N-th program (default: 1)",
    )
    parser.add_argument(
        "--size",
        type=chart_size,
        metavar="WxH",
        help="the picture's size in pixels (default: 800 wide, 190 high per panel)",
    )
    parser.add_argument("--from", dest="start_s", type=float, metavar="S", help="show from S seconds on")
    parser.add_argument("--to", dest="end_s", type=float, metavar="S", help="show up to S seconds")
    parser.add_argument(
        "--list", action="store_true", help="print the names of the values the trace has, and stop"
    )


def add_value_arguments(parser: argparse.ArgumentParser, option: str) -> None:
    """The option that names the values to draw (--values here, --plot-values for run and serve)."""
    parser.add_argument(
        option,
        action="append",
        type=_names,
        metavar="NAMES",
        help="comma-separated values to draw, e.g. in3,outB.speed,outC.speed (see them with "
        "`ev3sim2d plot TRACE --list`; default: the sensors whose reading changed and the motors that turned)",
    )


def chart_size(text: str) -> tuple[int, int]:
    """WxH in pixels, e.g. 800x600."""
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: give the size as WxH in pixels, e.g. 800x600") from None
    if not (100 <= width <= 8000 and 100 <= height <= 8000):
        raise argparse.ArgumentTypeError(f"{text!r}: width and height are 100 to 8000 pixels")
    return width, height


def _names(text: str) -> list[str]:
    return [name.strip() for name in text.split(",") if name.strip()]


def value_names(given: list[list[str]] | None) -> list[str] | None:
    """The names of repeated --values options, in order; None (the default chart) when none."""
    return [name for names in given or [] for name in names] or None


def matplotlib_missing() -> str | None:
    """The install hint when matplotlib cannot be imported, else None."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        from ..render.plot import INSTALL_HINT

        return INSTALL_HINT
    return None


def write_plot(
    trace: Trace, path: str, values: list[str] | None, robot: int = 0, option: str = "--plot-values", **chart
) -> None:
    """Write the chart as PNG; OSError with a message naming what to fix otherwise (an unknown value
    name lists the known ones; matplotlib missing says how to install it)."""
    from ..render.plot import plot_png

    try:
        data = plot_png(trace, values, robot, **chart)
    except KeyError as err:
        raise OSError(f"{option}: {err.args[0]} (each is told in `ev3sim2d plot TRACE --list`)") from None
    except ImportError as err:
        raise OSError(str(err)) from None
    try:
        write_file(path, data)
    except OSError as err:
        raise OSError(
            f"{path}: cannot write the plot ({err.strerror or err}); give a path in a folder you may write to"
        ) from None


def main(args) -> int:
    if not (args.png or args.list):
        return fail("nothing to do: give --png FILE to draw the chart, or --list to see the values")
    if not Path(args.trace).is_file():
        return fail(f"{args.trace}: no such trace file; write one with `ev3sim2d run PROG --trace FILE`")
    try:
        trace = Trace.load(args.trace)
    except Exception:  # noqa: BLE001 -- a zip, pickle, key or JSON error of a file that is not a trace
        return fail(
            f"{args.trace}: not a trace ev3sim2d can read; write one with `ev3sim2d run PROG --trace FILE`"
        )
    count = len(trace.robots)
    if not 1 <= args.robot <= count:
        return fail(f"--robot {args.robot}: the trace has {count} robot(s); give 1 to {count}")
    robot = args.robot - 1
    from ..render.plot import timelines

    if args.list:
        known = timelines(trace, robot)
        width = max(len(name) for name in known)
        for timeline in known.values():
            print(f"{timeline.name:<{width}}  {timeline.description}")
        return EXIT_OK
    if args.start_s is not None and args.end_s is not None and args.start_s >= args.end_s:
        return fail(f"--from {args.start_s} --to {args.end_s}: --from must come before --to")
    if (hint := matplotlib_missing()) is not None:
        return fail(hint)
    try:
        write_plot(
            trace,
            args.png,
            value_names(args.values),
            robot,
            option="--values",
            size_px=args.size,
            start_s=args.start_s,
            end_s=args.end_s,
        )
    except OSError as err:
        return fail(str(err))
    return EXIT_OK
