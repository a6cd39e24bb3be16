"""Display and Console: the LCD's size, its grid, and what update() sends."""

import pytest

from ev3dev2.console import Console
from ev3dev2.display import Display


@pytest.fixture
def brick(make_brick):
    return make_brick()


def test_display_is_the_ev3_lcd(brick):
    lcd = Display()
    assert (lcd.xres, lcd.yres) == (178, 128)
    assert lcd.shape == (178, 128)


def test_drawing_then_update_sends_the_picture(brick):
    lcd = Display()
    lcd.text_grid("Hello", x=2, y=3, font="luBS14")
    lcd.circle(clear_screen=False)
    lcd.rectangle(clear_screen=False, fill_color="white")
    lcd.line(clear_screen=False, width=3)
    lcd.point(clear_screen=False)
    lcd.update()

    feature, pixels = brick.calls[-1]
    assert feature == "display"
    assert pixels is None or len(pixels) == 178 * 128


def test_text_grid_refuses_cells_off_the_screen(brick):
    with pytest.raises(AssertionError, match="^grid columns must be between 0 and 21, 22 was requested$"):
        Display().text_grid("x", x=22)
    with pytest.raises(AssertionError, match="^grid rows must be between 0 and 11, 12 was requested$"):
        Display().text_grid("x", y=12)


def test_console_grid_follows_the_font():
    console = Console()
    assert (console.columns, console.rows) == (14, 5)
    console.set_font("Lat15-Terminus12x6")
    assert (console.columns, console.rows) == (29, 10)


def test_console_text_at_aligns_and_wraps():
    console = Console()
    console.text_at("Hi", column=3, row=2)
    console.text_at("end", column=14, row=3, alignment="R")
    console.text_at("abc", column=7, row=4, alignment="C")
    console.text_at("wrap me", column=12, row=5)

    assert console.lines == ["", "  Hi", "           end", "     abc", "           wra"]
    console.clear_to_eol(column=4, row=2)
    assert console.lines[1] == "  H"
    console.reset_console()
    assert console.lines == [""] * 5
