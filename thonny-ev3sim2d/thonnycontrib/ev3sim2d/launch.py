"""Run by the plug-in in the Python Thonny runs programs with: `ev3sim2d ARGUMENTS`, as on a command line."""

import sys

try:
    from ev3sim2d.cli import main
except ImportError:
    print(
        "ev3sim2d is not installed in the Python Thonny runs programs with "
        f"({sys.executable}): install it with Tools → Manage packages… (ev3sim2d)",
        file=sys.stderr,
    )
    sys.exit(2)

sys.exit(main(sys.argv[1:]))
