"""The brick's buttons: a wait ends at a button event, a press or a release, not at a button already down.

python-ev3dev2 2.1.0 (ev3dev-lang-python, tag ev3dev-stretch/2.1.0, ev3dev2/button.py): ButtonEVIO._wait
reads the buttons' input events (`for event in self.evdev_device.read_loop(): if event.type ==
evdev.ecodes.EV_KEY:`) and looks at the buttons at each one, so a wait that starts while a button is held
ends at the next event that meets it; ButtonCommon.process() compares the buttons with its last call
(`state_diff = new_state.symmetric_difference(old_state)`, the first call against `_state = set([])`) and
calls on_enter etc. for each change.  Scripted presses: `enter@1+1` is down from 1 s to 2 s.
"""

import subprocess
import sys
import textwrap

import pytest

from ev3sim2d.world.button_press import parse_press

HELD_THEN_PRESSED = [parse_press("enter@1+1"), parse_press("enter@3")]  # down 1-2 s, again 3-3.2 s

WAIT_WHILE_HELD = """
    import time
    from ev3dev2.button import Button
    btn = Button()
    time.sleep(1.5)
    print("held", btn.enter)
    btn.{wait}("enter")
    print("{wait}", round(time.monotonic() - 1000, 2))
"""


def seconds(result, index: int = 1) -> float:
    return float(result.trace.output[index].text.split()[-1])


def test_a_wait_for_a_press_started_while_the_button_is_held_ends_at_the_next_press(run):
    """2.1.0's _wait ends at an EV_KEY event only: enter, held when the wait starts at 1.5 s, is let go at
    2 s (an event that does not meet the wait) and pressed again at 3 s.  The wait used to end at once."""
    result = run(WAIT_WHILE_HELD.format(wait="wait_for_pressed"), presses=HELD_THEN_PRESSED)
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "held True"
    assert 3.0 <= seconds(result) < 3.03


def test_wait_for_bump_started_while_the_button_is_held_waits_for_a_new_press_and_its_release(run):
    """wait_for_bump is wait_for_pressed, then wait_for_released (2.1.0's ButtonCommon): the new press at
    3 s, its release at 3.2 s.  It used to end at the release of the press already held, at 2 s."""
    result = run(WAIT_WHILE_HELD.format(wait="wait_for_bump"), presses=HELD_THEN_PRESSED)
    assert result.status == "finished", result.reason
    assert 3.2 <= seconds(result) < 3.23


def test_a_wait_for_a_release_ends_at_a_button_event(run):
    """With no button down at 2.5 s, 2.1.0's wait_for_released("enter") waits for an event: the press at
    3 s leaves enter down, its release at 3.2 s ends the wait.  It used to end at once."""
    result = run(
        """
        import time
        from ev3dev2.button import Button
        btn = Button()
        time.sleep(2.5)
        btn.wait_for_released("enter")
        print("released", round(time.monotonic() - 1000, 2))
        """,
        presses=HELD_THEN_PRESSED,
    )
    assert result.status == "finished", result.reason
    assert 3.2 <= seconds(result, 0) < 3.23


MENU = """
    import time
    from ev3dev2.button import Button
    btn = Button()
    events = []
    btn.on_enter = lambda pressed: events.append((pressed, round(time.monotonic() - 1000, 2)))
    time.sleep(1.5)
    while time.monotonic() - 1000 < 3.5:
        btn.process()
    print(events)
"""


def test_process_calls_on_enter_at_each_change_in_a_menu_that_never_sleeps(run):
    """A menu loop that calls process() without sleeping: the first call (at 1.5 s) finds enter down
    where 2.1.0's empty `_state` had none (a change), then the release at 2 s, the press at 3 s and its
    release at 3.2 s, each once.  Each look at the buttons costs about 1 ms, as on the brick; the loop
    used to keep the clock still (and was stopped)."""
    first, second = run(MENU, presses=HELD_THEN_PRESSED), run(MENU, presses=HELD_THEN_PRESSED)
    assert first.status == "finished", first.reason
    assert first.trace.output[0].text == "[(True, 1.5), (False, 2.0), (True, 3.0), (False, 3.2)]"
    assert first.trace.fingerprint() == second.trace.fingerprint()


def test_a_wait_for_a_press_while_the_last_press_is_held_fails_when_it_is_let_go(run):
    """Nothing but the release of the held button is to come, and a release does not meet
    wait_for_pressed (on a brick the program would wait for ever): the run ends with NoButtonPress when
    the button is let go, at 2 s.  The wait used to end at once."""
    result = run(WAIT_WHILE_HELD.format(wait="wait_for_pressed"), presses=[parse_press("enter@1+1")])
    assert result.status == "error"
    assert result.error["type"] == "NoButtonPress"
    assert result.error["line"] == 7
    assert result.sim_time_s == pytest.approx(2.0, abs=0.015)


def test_ev3sim2d_run_with_a_held_press_and_a_new_one(tmp_path):
    """`ev3sim2d run prog.py --press enter@1+1 --press enter@3`: a wait for enter started at 1.5 s, while
    enter is held, ends at the press at 3 s (2.1.0's read_loop of button events)."""
    program = tmp_path / "prog.py"
    program.write_text(textwrap.dedent(WAIT_WHILE_HELD.format(wait="wait_for_pressed")))
    done = subprocess.run(
        [sys.executable, "-m", "ev3sim2d", "run", str(program), "--press", "enter@1+1", "--press", "enter@3"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "] held True" in done.stdout
    assert "] wait_for_pressed 3.01" in done.stdout
