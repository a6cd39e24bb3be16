"""The EV3 colour sensor's view of the floor: the seven colours it names and what it reads on them.

The readings are *modelled* values, chosen to be close to what an EV3 colour
sensor gives about 1 cm above LEGO-style printed mats; a real sensor varies
with height, light and paper.

- `id` is the number the sensor reports in COL-COLOR mode (0 = no colour).
- `reflected` is the COL-REFLECT reading (0..100, red LED light).
- `raw_rgb` is the RGB-RAW reading (each channel 0..1020; white paper is about 300).
- `display_rgb` is how the renderer draws the colour (0..255).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType


@dataclass(frozen=True)
class Ev3Color:
    """One colour the EV3 colour sensor can name, with its modelled readings."""

    name: str
    id: int
    display_rgb: tuple[int, int, int]
    reflected: float
    raw_rgb: tuple[float, float, float]


NO_COLOR_ID = 0
"""What COL-COLOR reports when it sees no colour it knows (mid greys, the edge of a line)."""

EV3_COLORS: MappingProxyType[str, Ev3Color] = MappingProxyType(
    {
        color.name: color
        for color in (
            Ev3Color("black", 1, (25, 25, 25), 5.0, (20.0, 22.0, 18.0)),
            Ev3Color("blue", 2, (30, 90, 200), 9.0, (30.0, 62.0, 150.0)),
            Ev3Color("green", 3, (40, 160, 70), 12.0, (40.0, 128.0, 52.0)),
            Ev3Color("yellow", 4, (245, 205, 30), 70.0, (280.0, 235.0, 60.0)),
            Ev3Color("red", 5, (210, 40, 40), 68.0, (260.0, 40.0, 30.0)),
            Ev3Color("white", 6, (255, 255, 255), 75.0, (300.0, 290.0, 240.0)),
            Ev3Color("brown", 7, (125, 80, 45), 16.0, (95.0, 58.0, 32.0)),
        )
    }
)
"""Colour name -> Ev3Color, in the order of the sensor's ids (black=1 .. brown=7)."""

COLOR_NAMES_BY_ID: tuple[str, ...] = ("NoColor", "Black", "Blue", "Green", "Yellow", "Red", "White", "Brown")
"""The names python-ev3dev2 gives the ids, indexed by id."""

_BLACK = EV3_COLORS["black"]
_WHITE = EV3_COLORS["white"]


def shade_reflected(shade: float) -> float:
    """COL-REFLECT on a grey of lightness `shade` (0 black .. 100 white): 5 + 0.70 * shade."""
    return _BLACK.reflected + (_WHITE.reflected - _BLACK.reflected) * shade / 100.0


def shade_color_id(shade: float) -> int:
    """COL-COLOR on a grey: white (6) from 60 up, black (1) up to 20, no colour (0) between."""
    if shade >= 60:
        return _WHITE.id
    if shade <= 20:
        return _BLACK.id
    return NO_COLOR_ID


def shade_raw_rgb(shade: float) -> tuple[float, float, float]:
    """RGB-RAW on a grey: the black reading blended towards the white one."""
    t = shade / 100.0
    return tuple(b + (w - b) * t for b, w in zip(_BLACK.raw_rgb, _WHITE.raw_rgb, strict=True))  # type: ignore[return-value]


def shade_display_rgb(shade: float) -> tuple[int, int, int]:
    """The grey to draw for `shade` (0 -> black, 100 -> white)."""
    level = max(0, min(255, round(shade * 255 / 100)))
    return (level, level, level)
