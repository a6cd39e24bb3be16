"""The `ev3sim2d` command: one subcommand per module in ev3sim2d/commands/."""

from __future__ import annotations

import argparse
import os
import sys

# numpy's BLAS would start a thread per core that spins after each call: the simulator has no use for it
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from .commands import (
    doctor,
    edit,
    examples,
    grade,
    join,
    lessons,
    live,
    mazes,
    plot,
    render,
    run,
    serve,
    show,
)

COMMANDS = [
    run,
    serve,
    join,
    mazes,
    examples,
    lessons,
    grade,
    render,
    plot,
    show,
    edit,
    live,
    doctor,
]  # a new subcommand: a module in commands/, one entry here


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="ev3sim2d",
        description="Run unmodified python-ev3dev2 programs on a simulated EV3 robot in a 2D grid world.",
    )
    parser.add_argument("--version", action=doctor.VersionAction)
    sub = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS:
        command.add_arguments(sub.add_parser(command.NAME, help=command.HELP, description=command.HELP))
    return parser


def _with_fixed_string_hashing() -> None:
    """Start again with PYTHONHASHSEED=0 unless it is set: a program that iterates over a set of
    strings must do the same thing in every run, as the fingerprint promises."""
    if os.environ.get("PYTHONHASHSEED") is None:
        os.environ["PYTHONHASHSEED"] = "0"
        sys.stdout.flush()
        sys.stderr.flush()
        os.execv(sys.executable, [sys.executable, "-m", "ev3sim2d", *sys.argv[1:]])


def main(argv: list[str] | None = None) -> int:
    if argv is None:  # the real command line, not a call from code
        _with_fixed_string_hashing()
    args = _parser().parse_args(argv)
    command = next(c for c in COMMANDS if c.NAME == args.command)
    try:
        status = command.main(args)
        sys.stdout.flush()  # here, where a reader that went away can still be answered quietly
        return status
    except BrokenPipeError:
        return _reader_gone()


def _reader_gone() -> int:
    """The reader of our output went away (`ev3sim2d grade ... | head`): end quietly, as Python's docs on
    SIGPIPE advise (what is left unflushed goes to devnull, so the exit does not fail again on it), with the
    status a shell expects of a writer whose reader is gone."""
    from .commands.exit_codes import EXIT_BROKEN_PIPE

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())
    os.close(devnull)
    return EXIT_BROKEN_PIPE


if __name__ == "__main__":
    sys.exit(main())
