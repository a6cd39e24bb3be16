"""Exit statuses of the ev3sim2d command, and how a command reports a user's mistake.

0 all went well (grade: every program scored at least --pass-percent); 1 a program failed (grade: some
program scored less); 2 a usage error (a wrong option, file or lesson: the message says which); 3 `run`:
a program hung; 4 an internal error (a bug in ev3sim2d: a traceback is printed); 130 interrupted
(Ctrl+C); 141 the reader of the output went away (`... | head`), as for any command a SIGPIPE ends.
"""

import sys

EXIT_OK, EXIT_PROGRAM_ERROR, EXIT_USAGE, EXIT_HUNG, EXIT_INTERNAL = 0, 1, 2, 3, 4
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141  # 128 + SIGPIPE: what a shell shows for a writer whose reader is gone


def fail(message: str, code: int = EXIT_USAGE) -> int:
    """Print `ev3sim2d: error: message` on stderr and return the exit status."""
    print(f"ev3sim2d: error: {message}", file=sys.stderr)
    return code
