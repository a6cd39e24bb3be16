"""Shared helpers: small worlds written inline as text, programs written inline as source."""

import textwrap

import pytest

from ev3sim2d.run import run_programs
from ev3sim2d.world.maze_file import parse_maze


def arena(width=20, height=20, cell_cm=12, start="x_cm: 60\n  y_cm: 120\n  heading_deg: 0", inner=None, extra=""):
    """A walled arena of width × height cells; `inner` replaces the rows inside the border."""
    rows = ["#" * width]
    inner = inner or ["#" + "." * (width - 2) + "#"] * (height - 2)
    rows += inner
    rows.append("#" * width)
    grid = "\n".join("  " + r for r in rows)
    text = f"title: test\ncell_cm: {cell_cm}\ngrid: |\n{grid}\nstart:\n  {start}\n{extra}"
    return parse_maze(text, "<test arena>")


@pytest.fixture
def run(tmp_path):
    """run(source, world, **options) -> RunResult, the source written to a file prog.py."""
    counter = {"n": 0}

    def _run(source, world=None, **options):
        counter["n"] += 1
        path = tmp_path / f"prog{counter['n']}.py"
        path.write_text(textwrap.dedent(source))
        options.setdefault("time_limit_s", 30)
        options.setdefault("hang_after_s", 2.0)
        return run_programs([path], world or arena(), **options)

    return _run
