"""Shared fixtures (run a program written inline as source; the stand-ins for other systems), and
`needs_linux`: the mark of a test that needs a feature of Linux's that Windows or macOS lacks.

    @pytest.mark.needs_linux("fork", "proc")
    def test_...

skips the test, naming the feature, where this system lacks one of them (a check of the feature
itself, never of the system's name), and does nothing where it has them all: on Linux every test
runs.  The features, and how each is checked: tests/linux_features.py.
"""

import textwrap

import pytest

from ev3sim2d.simulator.run import run_programs
from tests import linux_features
from tests.inline_world import arena


@pytest.fixture
def run(tmp_path):
    """run(source, world, **options) -> RunResult, the source written to a file prog.py."""
    counter = {"n": 0}

    def _run(source, world=None, **options):
        counter["n"] += 1
        path = tmp_path / f"prog{counter['n']}.py"
        path.write_text(textwrap.dedent(source), encoding="utf-8")
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


# ---------------------------------------------------------------- what a test needs of Linux


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "needs_linux(*features): skip where this system lacks one of these features of Linux's "
        f"(tests/linux_features.py: {', '.join(linux_features.FEATURES)})",
    )


def pytest_collection_modifyitems(config, items):
    for item in items:
        names = [name for mark in item.iter_markers("needs_linux") for name in mark.args]
        reason = linux_features.skip_reason(*names) if names else None
        if reason:
            item.add_marker(pytest.mark.skip(reason=reason))
