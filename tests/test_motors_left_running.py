"""A program that ends with its motors running is told what a brick would do.

brickrun (ev3dev/brickrun, src/brickrun.vala: after the program's main loop ends,
`stop_motors (... "tacho-motor"), "reset")`), which Brickman starts every program with
(brickman, src/controller/FileBrowserController.vala: "brickrun takes care of switching consoles,
stopping motors, etc."), resets every tacho motor when the program ends, so the robot stops; a
program started over SSH with `python3 prog.py` has no brickrun around it, and its motors keep
running.  A student who tests over SSH sees a robot that drives on; one who starts it from the
brick sees it stop.  The run says so.
"""

import json

import pytest

from ev3sim2d import cli

LEFT_RUNNING = """
from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
import time
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on(30, 30)
time.sleep(1)
"""


def _run(tmp_path, monkeypatch, capsys, source, *options):
    (tmp_path / "prog.py").write_text(source)
    monkeypatch.chdir(tmp_path)
    status = cli.main(["run", "prog.py", "--time", "5", "--summary", "s.json", *options])
    err = capsys.readouterr().err
    return status, err, json.loads((tmp_path / "s.json").read_text())


def test_motors_left_running_are_named_with_what_brickman_and_ssh_do(tmp_path, monkeypatch, capsys):
    status, err, summary = _run(tmp_path, monkeypatch, capsys, LEFT_RUNNING)
    assert status == 0
    note = next(line for line in err.splitlines() if line.startswith("ev3sim2d: note: "))
    assert "motors outB, outC were still running" in note
    assert "started from Brickman ends with its motors reset" in note
    assert "over SSH (`python3 prog.py`) leaves them running" in note
    assert summary["notes"] == [note.removeprefix("ev3sim2d: note: ")]


def test_a_program_that_crashes_with_its_motors_running_is_told_too(tmp_path, monkeypatch, capsys):
    status, err, summary = _run(tmp_path, monkeypatch, capsys, LEFT_RUNNING + "1 / 0\n")
    assert summary["status"] == "error"
    assert "motors outB, outC were still running" in summary["notes"][0]


@pytest.mark.parametrize(
    "ending",
    [
        "tank.off()\n",  # stopped
        "tank.on_for_seconds(30, 30, 1)\n",  # a run that ends by itself
        "tank.off(brake=False)\n",
    ],
)
def test_a_program_that_stops_its_motors_gets_no_note(tmp_path, monkeypatch, capsys, ending):
    source = LEFT_RUNNING.replace("time.sleep(1)\n", "time.sleep(1)\n" + ending)
    status, err, summary = _run(tmp_path, monkeypatch, capsys, source)
    assert status == 0 and summary["notes"] == []
    assert "note:" not in err


def test_a_program_stopped_at_the_time_limit_gets_no_note(tmp_path, monkeypatch, capsys):
    """Stopped by the simulator, not ended by itself: what a brick does at its own end does not apply."""
    status, err, summary = _run(tmp_path, monkeypatch, capsys, LEFT_RUNNING + "time.sleep(60)\n")
    assert summary["status"] == "time_limit" and summary["notes"] == []
