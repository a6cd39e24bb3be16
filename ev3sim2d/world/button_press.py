"""Scripted presses of the brick's buttons: `enter@2.0` presses Enter at 2.0 s for 0.2 s.

A program that waits for a button runs headless when its presses are scripted,
on the command line (`--press enter@2.0`) or in the world file
(`buttons: [enter@2.0, down@5+1.5]`).  `BUTTON@SECONDS[+HOLD]`: HOLD, the time
the button stays down, is 0.2 s unless given.
"""

from __future__ import annotations

from dataclasses import dataclass

from .file_limits import MAX_BUTTON_TIME_S

BUTTONS = ("up", "down", "left", "right", "enter", "backspace")
DEFAULT_HOLD_S = 0.2


@dataclass(frozen=True)
class ButtonPress:
    """One press: which button, when (virtual seconds) and for how long."""

    button: str
    at_s: float
    hold_s: float = DEFAULT_HOLD_S

    def down_at(self, t_s: float) -> bool:
        return self.at_s <= t_s < self.at_s + self.hold_s

    def __str__(self) -> str:
        return f"{self.button}@{self.at_s:g}+{self.hold_s:g}"


def parse_press(text: str) -> ButtonPress:
    """`enter@2.0` or `enter@2.0+0.5`; ValueError saying what to write otherwise."""
    usage = f"write BUTTON@SECONDS or BUTTON@SECONDS+HOLD, e.g. enter@2.0; buttons: {', '.join(BUTTONS)}"
    button, at, rest = str(text).strip().partition("@")
    button = button.strip().lower()
    if not at:
        raise ValueError(f"'{text}' is not a button press; {usage}")
    if button not in BUTTONS:
        raise ValueError(f"'{button}' is not an EV3 button; {usage}")
    when, plus, hold = rest.partition("+")
    try:
        at_s = float(when)
        hold_s = float(hold) if plus else DEFAULT_HOLD_S
    except ValueError:
        raise ValueError(f"'{text}': the time must be a number of seconds; {usage}") from None
    if not (0 <= at_s <= MAX_BUTTON_TIME_S and 0 < hold_s <= MAX_BUTTON_TIME_S):
        raise ValueError(
            f"'{text}': the time must be 0 or more and the hold more than 0, each at most "
            f"{MAX_BUTTON_TIME_S:g} s (a day); {usage}"
        )
    return ButtonPress(button, at_s, hold_s)
