"""Fixtures for the ev3dev2 shim's tests: a FakeBrick connected through _link, on a virtual clock."""

import sys
import time

import pytest

from ev3dev2 import _link

from .fake_brick import FakeBrick


@pytest.fixture
def make_brick(monkeypatch):
    """Returns a function that connects a FakeBrick with the given device specs (and patches time)."""
    bricks = []

    def make(*specs):
        devices = []
        for spec in specs:
            devices.extend(spec if isinstance(spec, list) else [spec])
        brick = FakeBrick(devices)
        monkeypatch.setattr(time, "time", brick.time)
        monkeypatch.setattr(time, "sleep", brick.sleep)
        _link.connect(brick)
        bricks.append(brick)
        return brick

    yield make
    _link.disconnect()


@pytest.fixture(scope="package", autouse=True)
def forget_the_shim_afterwards():
    """Leave no ev3dev2 module imported: other tests check that a simulated run leaves none behind."""
    yield
    _link.disconnect()
    for name in [name for name in sys.modules if name == "ev3dev2" or name.startswith("ev3dev2.")]:
        del sys.modules[name]


API_SHARE = pytest.StashKey[str]()


def pytest_terminal_summary(terminalreporter, config):
    """The share of python-ev3dev2's API the shim matches (test_api_conformance.py), under the results."""
    share = config.stash.get(API_SHARE, None)
    if share:
        terminalreporter.write_line(f"ev3dev2 shim against python-ev3dev2 2.1.0: {share}")
