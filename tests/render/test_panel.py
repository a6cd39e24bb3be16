"""The panel's words for what the brick knows."""

import pytest

from ev3sim2d.render.panel import led_color_name, motor_state_word, sensor_value_text


@pytest.mark.parametrize(
    ("kind", "mode", "values", "text"),
    [
        ("touch", "TOUCH", [1], "pressed"),
        ("touch", "TOUCH", [0], "released"),
        ("color", "COL-REFLECT", [42], "42 %"),
        ("color", "COL-COLOR", [3], "Green"),
        ("color", "RGB-RAW", [300, 290, 240], "300 290 240"),
        ("ultrasonic", "US-DIST-CM", [2550], "255.0 cm"),
        ("ultrasonic", "US-DIST-IN", [167], "16.7 in"),
        ("gyro", "GYRO-ANG", [-90], "-90°"),
        ("gyro", "GYRO-G&A", [10, -3], "10° -3°/s"),
        ("infrared", "IR-PROX", [57], "57 %"),
        ("nxt-light", "REFLECT", [456], "45.6 %"),
        ("touch", "TOUCH", [], "—"),
    ],
)
def test_sensor_values_in_words_and_units(kind, mode, values, text):
    assert sensor_value_text(kind, mode, values) == text


def test_led_colours_by_name():
    assert led_color_name(0, 0) == "off"
    assert led_color_name(255, 0) == "red"
    assert led_color_name(0, 255) == "green"
    assert led_color_name(255, 255) == "amber"
    assert led_color_name(255, 128) == "orange"
    assert led_color_name(25, 255) == "yellow"


def test_the_state_word_that_matters_most():
    assert motor_state_word(0) == "stopped"
    assert motor_state_word(1) == "running"
    assert motor_state_word(1 | 16) == "stalled"
    assert motor_state_word(4) == "holding"
