"""Scripted button presses let a program that waits for a button run headless."""

import subprocess
import sys

from ev3sim2d.world.button_press import ButtonPress, parse_press

WAIT_FOR_ENTER = """
    import time
    from ev3dev2.button import Button
    btn = Button()
    btn.wait_for_bump("enter")
    print("go", round(time.monotonic() - 1000, 2))
"""


def test_parse_press():
    assert parse_press("enter@2") == ButtonPress("enter", 2.0, 0.2)
    assert parse_press("Down@1.5+3") == ButtonPress("down", 1.5, 3.0)
    for bad in ("enter", "jump@1", "enter@soon", "enter@-1"):
        try:
            parse_press(bad)
        except ValueError as err:
            assert "BUTTON@SECONDS" in str(err)
        else:
            raise AssertionError(bad)


def test_a_program_waiting_for_enter_continues_after_a_scripted_press(run):
    result = run(WAIT_FOR_ENTER, presses=[parse_press("enter@2.0")])
    assert result.status == "finished", result.reason
    (line,) = [o.text for o in result.trace.output]
    assert line.startswith("go 2.2")  # pressed at 2.0, released 0.2 s later


def test_presses_can_come_from_the_world_file(run):
    from tests.inline_world import arena

    result = run(WAIT_FOR_ENTER, arena(extra="buttons: [enter@1.0+0.5]\n"))
    assert result.trace.output[0].text.startswith("go 1.5")


def test_waiting_for_a_button_nobody_will_press_is_reported_not_hung(run):
    result = run(WAIT_FOR_ENTER)
    assert result.status == "error"
    assert result.error["type"] == "NoButtonPress"
    assert "--press enter@2.0" in result.error["message"]
    assert result.wall_time_s < 2


def test_the_command_line_takes_press(tmp_path):
    prog = tmp_path / "p.py"
    prog.write_text("from ev3dev2.button import Button\nButton().wait_for_pressed('up')\nprint('up!')\n")
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(prog), "--press", "up@3"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    assert "] up!" in done.stdout
    bad = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(prog), "--press", "middle@3"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert bad.returncode == 2 and "not an EV3 button" in bad.stderr
