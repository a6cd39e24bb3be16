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


@pytest.fixture(scope="session")
def other_systems(tmp_path_factory):
    """{"windows": path, "macos": path}: a Windows-like and a macOS-like Python
    (tests/portable/other_system.py), made of this one where it is Linux's (skip elsewhere: the real
    systems run the suite themselves)."""
    from ev3sim2d.brick.sandbox import linux_kernel
    from tests.portable.launcher import launcher_for

    if not linux_kernel():
        pytest.skip("the stand-ins for other systems are made of a Linux Python")
    folder = tmp_path_factory.mktemp("other-systems")
    return {kind: launcher_for(kind, folder) for kind in ("windows", "macos")}
