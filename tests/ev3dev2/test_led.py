"""Leds: colours become brightness writes on the four 'leds' devices, as python-ev3dev2 2.1.0 makes them."""

import pytest

from ev3dev2.led import Led, Leds

from .fake_brick import leds

RED_LEFT, RED_RIGHT = "led0:red:brick-status", "led1:red:brick-status"
GREEN_LEFT, GREEN_RIGHT = "led0:green:brick-status", "led1:green:brick-status"


@pytest.fixture
def brick(make_brick):
    return make_brick(leds())


def test_set_color_scales_each_led_of_the_group(brick):
    lights = Leds()
    lights.set_color("LEFT", "AMBER")
    lights.set_color("RIGHT", "ORANGE", pct=0.5)

    assert brick.writes() == [
        (RED_LEFT, "brightness", "255"),
        (GREEN_LEFT, "brightness", "255"),
        (RED_RIGHT, "brightness", "127"),
        (GREEN_RIGHT, "brightness", "63"),
    ]
    assert brick.reads().count((RED_LEFT, "max_brightness")) == 1


def test_set_color_accepts_a_tuple(brick):
    Leds().set_color("RIGHT", (0.2, 1))
    assert brick.writes() == [(RED_RIGHT, "brightness", "51"), (GREEN_RIGHT, "brightness", "255")]


def test_invalid_colors_and_groups_are_refused_as_upstream(brick):
    lights = Leds()
    with pytest.raises(
        AssertionError,
        match="^PINK is an invalid LED color, valid choices are BLACK, RED, GREEN, AMBER, ORANGE, YELLOW$",
    ):
        lights.set_color("LEFT", "PINK")
    with pytest.raises(
        AssertionError, match="^MIDDLE is an invalid LED group, valid choices are LEFT, RIGHT$"
    ):
        lights.set_color("MIDDLE", "RED")


def test_all_off_and_reset(brick):
    lights = Leds()
    lights.all_off()
    lights.reset()

    assert brick.writes() == [
        (RED_LEFT, "brightness", "0"),
        (RED_RIGHT, "brightness", "0"),
        (GREEN_LEFT, "brightness", "0"),
        (GREEN_RIGHT, "brightness", "0"),
        (RED_LEFT, "brightness", "0"),
        (GREEN_LEFT, "brightness", "255"),
        (RED_RIGHT, "brightness", "0"),
        (GREEN_RIGHT, "brightness", "255"),
    ]


def test_set_writes_any_attribute(brick):
    Leds().set("LEFT", brightness_pct=0.5, trigger="timer")
    assert brick.writes() == [
        (RED_LEFT, "brightness", "127"),
        (RED_LEFT, "trigger", "timer"),
        (GREEN_LEFT, "brightness", "127"),
        (GREEN_LEFT, "trigger", "timer"),
    ]


def test_led_trigger_and_brightness(brick):
    led = Led(name_pattern=GREEN_RIGHT, desc="green_right")
    assert str(led) == "green_right"
    assert led.trigger == "none"
    assert led.triggers == ["none", "timer", "heartbeat", "default-on"]
    led.brightness = 51
    assert led.brightness_pct == pytest.approx(0.2)


def test_animations_run_for_their_duration(brick):
    start = brick.clock
    Leds().animate_flash("RED", sleeptime=0.5, duration=2)

    assert brick.clock - start == pytest.approx(2)
    red_left = [value for (name, _, value) in brick.writes() if name == RED_LEFT]
    assert red_left == ["255", "0", "255", "0", "255"]


def test_animation_in_a_thread_stops_when_asked(brick):
    lights = Leds()
    lights.animate_cycle(("RED", "GREEN"), duration=None, block=False)
    assert lights.animate_thread_id is not None
    lights.animate_stop()

    assert lights.animate_thread_id is None and lights.animate_thread_stop is False
