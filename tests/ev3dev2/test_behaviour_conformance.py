"""
The shim does what the real python-ev3dev2 2.1.0 does: every scenario of
conformance/scenarios.py, run on a FakeBrick, must write the same attributes with the same
values in the same order, raise the same exception (type, module and message), record the
same values and make the same reads and polls as the real library did when
conformance/record_upstream_writes.py recorded it into conformance/upstream_writes.json.
"""

import json
import os

import pytest

from .conformance.record_upstream_writes import FIXTURE, digest, outcome, run_script
from .conformance.scenarios import SCENARIOS

with open(FIXTURE, encoding="utf-8") as _file:
    UPSTREAM = json.load(_file)

RECORD_AGAIN = "record it again: python tests/ev3dev2/conformance/record_upstream_writes.py"


def test_every_scenario_is_recorded_and_no_recording_is_left_over():
    assert sorted(UPSTREAM) == sorted(SCENARIOS), RECORD_AGAIN


@pytest.mark.parametrize("name", sorted(SCENARIOS))
def test_shim_does_what_python_ev3dev2_does(name, make_brick):
    devices, script = SCENARIOS[name]
    theirs = UPSTREAM.get(name)
    assert theirs is not None and theirs["digest"] == digest(devices, script), (
        f"scenario {name} changed since it was recorded; {RECORD_AGAIN}"
    )

    brick = make_brick(json.loads(json.dumps(devices)))
    records, exception = run_script(script)
    ours = outcome(brick.log, records, exception)

    assert ours["writes"] == theirs["writes"]
    assert ours["exception"] == theirs["exception"]
    assert ours["records"] == theirs["records"]
    assert ours["log"] == theirs["log"]


def test_the_fixture_is_what_the_recorder_writes():
    """It is committed as recorded: no hand edits."""
    from .conformance.record_upstream_writes import format_fixture

    with open(FIXTURE, encoding="utf-8") as file:
        assert file.read() == format_fixture(UPSTREAM)


@pytest.mark.skipif(
    not os.path.isfile(
        os.path.join(
            os.environ.get("EV3DEV2_UPSTREAM", "/tmp/ev3src/python-ev3dev2-2.1.0"), "ev3dev2", "motor.py"
        )
    ),
    reason="the python-ev3dev2 2.1.0 source is not here (set EV3DEV2_UPSTREAM to its folder)",
)
def test_the_fixture_is_what_python_ev3dev2_does_today(tmp_path, monkeypatch):
    """Where the real library's source is at hand, recording again gives the committed fixture."""
    from .conformance import record_upstream_writes

    monkeypatch.setattr(record_upstream_writes, "FIXTURE", str(tmp_path / "upstream_writes.json"))
    source = os.environ.get("EV3DEV2_UPSTREAM", "/tmp/ev3src/python-ev3dev2-2.1.0")
    assert record_upstream_writes.record(source) == UPSTREAM
