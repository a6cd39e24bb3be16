"""Button: the brick's buttons, read with _link.call('buttons')."""

import pytest

from ev3dev2.button import Button


@pytest.fixture
def brick(make_brick):
    return make_brick()


def press_over_time(brick, *states):
    """Make the buttons go through ``states`` (lists of names), one per look; the last one stays."""
    states = list(states)

    def call(feature, *args):
        brick.calls.append([feature, *args])
        if args:  # ("buttons", "wait"): a wait with no end checks that a press will come
            return None
        return states.pop(0) if len(states) > 1 else states[0]

    brick.call = call


def test_pressed_buttons_in_upstreams_order(brick):
    brick.buttons = ["enter", "up"]
    buttons = Button()

    assert buttons.buttons_pressed == ["up", "enter"]
    assert buttons.enter and buttons.up and not buttons.backspace
    assert buttons.any()
    assert buttons.check_buttons(["enter", "up"])
    assert not buttons.check_buttons(["enter"])


def test_wait_for_bump(brick):
    press_over_time(brick, [], [], ["left"], ["left"], [])
    start = brick.clock

    assert Button().wait_for_bump("left") is True
    assert brick.clock - start == pytest.approx(0.03)


def test_wait_times_out(brick):
    start = brick.clock
    assert Button().wait_for_pressed(["up", "down"], timeout_ms=200) is False
    assert brick.clock - start == pytest.approx(0.2, abs=0.011)
    assert Button().wait_for_released("up", timeout_ms=200) is False  # no button event within 200 ms


def test_process_calls_the_handlers_of_changed_buttons(brick):
    press_over_time(brick, ["enter"], [])
    buttons = Button()
    events = []
    buttons.on_enter = lambda pressed: events.append(("enter", pressed))
    buttons.on_change = events.append

    buttons.process()
    buttons.process()

    assert events == [("enter", True), [("enter", True)], ("enter", False), [("enter", False)]]
