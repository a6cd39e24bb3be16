"""Exit statuses of the ev3sim2d command, and how a command reports a user's mistake."""

import sys

EXIT_OK, EXIT_PROGRAM_ERROR, EXIT_USAGE, EXIT_HUNG, EXIT_INTERRUPTED = 0, 1, 2, 3, 130


def fail(message: str, code: int = EXIT_USAGE) -> int:
    """Print `ev3sim2d: error: message` on stderr and return the exit status."""
    print(f"ev3sim2d: error: {message}", file=sys.stderr)
    return code
