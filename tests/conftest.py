"""Shared fixture: run a program written inline as source."""

import textwrap

import pytest

from ev3sim2d.simulator.run import run_programs
from tests.inline_world import arena


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
