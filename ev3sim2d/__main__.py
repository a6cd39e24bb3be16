"""`python -m ev3sim2d` is the `ev3sim2d` command."""

import sys

from .cli import main

sys.exit(main())
