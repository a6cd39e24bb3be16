"""The EV3 colour sensor's view of the floor: the seven colours it names and what it reads on them.

The readings are *modelled* values, chosen to be close to what an EV3 colour
sensor gives about 1 cm above LEGO-style printed mats; a real sensor varies
with height, light and paper.  A world file may calibrate them for its own
floor (`surfaces:`, read into a `Surfaces`): what white, black and each colour
read in reflected light and RGB-RAW; greys follow black and white.

- `id` is the number the sensor reports in COL-COLOR mode (0 = no colour).
- `reflected` is the COL-REFLECT reading (0..100, red LED light).
- `raw_rgb` is the RGB-RAW reading (each channel 0..1020; white paper is about 300).
- `display_rgb` is how the renderer draws the colour (0..255).
"""

from __future__ import annotations

from collections.abc import Mapping
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


# -- a world's own floor -------------------------------------------------------------------------

REFLECT_RANGE = (0.0, 100.0)
"""COL-REFLECT, as the driver gives it (lego-linux-drivers ev3_uart_sensor_defs.c: pct, 0-100)."""
RGB_RAW_RANGE = (0.0, 1020.0)
"""RGB-RAW per channel, as the driver gives it (0-1020)."""


class Surfaces:
    """What the colour sensor reads on one world's floor: COL-REFLECT and RGB-RAW on each EV3 colour.

    A world file's `surfaces:` calibrates some colours (docs/world-files.md), the others keep the
    modelled values of EV3_COLORS.  A grey of shade s (0 black .. 100 white, the `0`-`9` legend digits)
    reads black's values blended towards white's, s % of the way, as greys do by default; so a
    calibrated white and black carry the greys with them.  COL-COLOR ids do not change: which colour
    the sensor names is the cell's, not its readings'.
    """

    def __init__(self, calibrated: Mapping[str, Mapping[str, object]] | None = None) -> None:
        """`calibrated`: colour name -> {"reflect": COL-REFLECT, "rgb_raw": (r, g, b)}, either or both."""
        self.calibrated: dict[str, dict[str, float | tuple[float, float, float]]] = {}
        self._reflected = {name: color.reflected for name, color in EV3_COLORS.items()}
        self._raw_rgb = {name: tuple(color.raw_rgb) for name, color in EV3_COLORS.items()}
        for name, values in (calibrated or {}).items():
            if name not in EV3_COLORS:
                raise ValueError(f"unknown colour {name!r}; the EV3 colours are {', '.join(EV3_COLORS)}")
            unknown = set(values) - {"reflect", "rgb_raw"}
            if unknown:
                raise ValueError(
                    f"{name}: unknown readings {sorted(unknown)}; a colour has `reflect` and `rgb_raw`"
                )
            own = self.calibrated[name] = {}
            if "reflect" in values:
                own["reflect"] = self._reflected[name] = float(values["reflect"])  # type: ignore[arg-type]
            if "rgb_raw" in values:
                red, green, blue = (float(v) for v in values["rgb_raw"])  # type: ignore[union-attr]
                own["rgb_raw"] = self._raw_rgb[name] = (red, green, blue)

    @property
    def is_default(self) -> bool:
        """Whether nothing is calibrated (every reading is the modelled one)."""
        return not self.calibrated

    def reflected(self, color: str | None, shade: float) -> float:
        """COL-REFLECT on a floor of `color`, or of grey `shade` when color is None."""
        if color is not None:
            return self._reflected[color]
        black, white = self._reflected["black"], self._reflected["white"]
        return black + (white - black) * shade / 100.0

    def raw_rgb(self, color: str | None, shade: float) -> tuple[float, float, float]:
        """RGB-RAW on a floor of `color`, or of grey `shade` when color is None."""
        if color is not None:
            return self._raw_rgb[color]  # type: ignore[return-value]
        t = shade / 100.0
        black, white = self._raw_rgb["black"], self._raw_rgb["white"]
        return tuple(b + (w - b) * t for b, w in zip(black, white, strict=True))  # type: ignore[return-value]

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Surfaces) and self.calibrated == other.calibrated

    def __hash__(self) -> int:
        return hash(
            tuple(sorted((name, tuple(sorted(values.items()))) for name, values in self.calibrated.items()))
        )

    def __repr__(self) -> str:
        return f"Surfaces({self.calibrated!r})"


DEFAULT_SURFACES = Surfaces()
"""The modelled floor: nothing calibrated."""
