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
    init,
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
    init,
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


def _program_arguments(argv: list[str]) -> tuple[list[str], list[str]]:
    """`ev3sim2d run PROG... -- ARG...`: what follows the first -- goes to the programs (their sys.argv[1:]),
    not to ev3sim2d, for a command that passes arguments on (PASSES_ARGUMENTS)."""
    if "--" not in argv:
        return argv, []
    at = argv.index("--")
    words = [a for a in argv[:at] if not a.startswith("-")]
    passing = {c.NAME for c in COMMANDS if getattr(c, "PASSES_ARGUMENTS", False)}
    if not words or words[0] not in passing:
        return argv, []
    return argv[:at], argv[at + 1 :]


def _console_never_fails() -> None:
    """What a program prints, its file names and every message reach a console whatever it can show:
    a Windows console or a redirected output there is cp1252 (or cp437), a Linux one under LC_ALL=C is
    ASCII; a character it cannot show is written as a backslash escape (\u03c0), never an error."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)
        if reconfigure is not None:
            try:
                reconfigure(errors="backslashreplace")
            except (ValueError, OSError):
                pass


def main(argv: list[str] | None = None) -> int:
    if argv is None:  # the real command line, not a call from code
        _console_never_fails()
    argv, program_arguments = _program_arguments(list(sys.argv[1:] if argv is None else argv))
    args = _parser().parse_args(argv)
    args.program_arguments = program_arguments
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
