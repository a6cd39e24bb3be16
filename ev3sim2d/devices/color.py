"""EV3 colour sensor: reflected light, colour, ambient and raw values of the floor, or of a wall ahead.

Facing down, the sensor sees a small square spot (`spot_cm`, default 1.5 cm) and
reports the area-weighted mean of the cells under it, so its reading changes
smoothly across the edge of a line, as a real sensor's does and proportional
line following needs.  Reflected light per shade and colour: see
world/colors.py (black tape about 5, white paper about 75).

Facing forward (`facing: forward`: some maze solvers use it as a short-range
distance sensor), it does not see the floor: it reads the light its LED gets
back from a wall (walls and robots are white to it) on its axis, by the wall's distance d:

    share(d) = 1                                 d <= 1 cm
             = ((1/d)^2 - (1/10)^2) / (1 - (1/10)^2)   1 cm < d < 10 cm
             = 0                                 d >= 10 cm (or nothing there)

and reflected light = 75 (white paper at the sensor's working distance) x
share(d): 75 within 1 cm, 18 at 2 cm, 8 at 3 cm, 2 at 5 cm, 0 from 10 cm.  This is
a modelling choice, not a measurement: the LED's light on the wall falls with
the square of the distance (a small source), the sensor is made to read a
surface about 1 cm away (so the curve is flat closer than that), and the
tail is cut so that it reaches 0 at 10 cm.  With nothing in front it reads 0:
COL-REFLECT is the LED-on reading less the LED-off one (the driver's
REF-RAW footnote: reflect = value1 - value0), so room light cancels out.
COL-COLOR names the wall (white, 6) while share(d) >= 0.2 (within about 2 cm), else
0 (no colour); COL-AMBIENT is the room's light, as facing down.

Raw modes, as the lego-ev3-color driver documents them (lego-linux-drivers
sensors/ev3_uart_sensor_defs.c, LEGO_EV3_COLOR): REF-RAW is (ADC with the LED
on, ADC with it off); more light gives a lower ADC reading, so the LED-on value
is the LED-off one less the red light reflected.  RGB-RAW is red, green and
blue reflected (LEDs on less LEDs off) and the LEDs-off ADC reading.  COL-CAL
has 3 values (the driver: num_values 3 of 4 data sets, u16), whose meaning the
driver does not know; here the red, green and blue reflected.  The LEDs-off ADC
reading is LED_OFF_ADC less 2 per % of room light: a modelling choice.
"""

from __future__ import annotations

from ..world.colors import EV3_COLORS
from .sensor import LegoSensor, Mode

DEFAULT_SPOT_CM = 1.5
LED_OFF_ADC = 1000.0  # the ADC reading with the LEDs off in a dark room (more light: lower)
# a forward-facing sensor: a white wall, read from NEAR_CM (full) to FAR_CM (nothing)
WALL = EV3_COLORS["white"]
NEAR_CM = 1.0
FAR_CM = 10.0
COLOR_SHARE = 0.2  # COL-COLOR names the wall from this share of the light up (within about 2 cm)


def wall_share(distance_cm: float | None) -> float:
    """The share of the light at NEAR_CM that a wall distance_cm ahead sends back (see the module's doc)."""
    if distance_cm is None or distance_cm >= FAR_CM:
        return 0.0
    if distance_cm <= NEAR_CM:
        return 1.0
    far = (NEAR_CM / FAR_CM) ** 2
    return ((NEAR_CM / distance_cm) ** 2 - far) / (1.0 - far)


class ColorSensor(LegoSensor):
    KIND = "color"
    DRIVER = "lego-ev3-color"
    MODES = {
        "COL-REFLECT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-AMBIENT": Mode(1, 0, "pct", "s8", 0, 100),
        "COL-COLOR": Mode(1, 0, "col", "s8", 0, 7, noisy=False),
        "REF-RAW": Mode(2, 0, "", "s16", 0, 1023),
        "RGB-RAW": Mode(4, 0, "", "s16", 0, 1023),
        "COL-CAL": Mode(3, 0, "", "u16", 0, 65535, noisy=False),
    }
    OPTIONS = {"spot_cm": (DEFAULT_SPOT_CM, "cm", "diameter of the floor spot the sensor sees")}
    LABEL = "colour"
    FLOOR_SPOT = True  # (facing forward it reads a wall)

    def __init__(self, address, spec, surroundings, floor, ambient: float = 10.0) -> None:
        super().__init__(address, spec, surroundings)
        self.floor = floor
        self.ambient = ambient
        self.half = float(spec.options.get("spot_cm", DEFAULT_SPOT_CM)) / 2.0
        self.facing_forward = getattr(spec, "facing", "down") == "forward"
        if self.facing_forward:  # chosen once, so that the floor's hot path checks nothing
            self.measure = self.measure_forward  # type: ignore[method-assign]

    def wall_share(self) -> float:
        """Facing forward: the share of the full reading the wall on the sensor's axis sends back."""
        x, y, facing = self.position()
        return wall_share(self.around.ray(x, y, facing, FAR_CM))

    def measure_forward(self, mode: str) -> tuple[float, ...]:
        """The values of `mode` facing forward: a wall ahead, never the floor."""
        if mode == "COL-AMBIENT":
            return (self.ambient,)
        share = self.wall_share()
        if mode == "COL-REFLECT":
            return (WALL.reflected * share,)
        if mode == "COL-COLOR":
            return (WALL.id if share >= COLOR_SHARE else 0,)
        return self._raw(mode, [c * share for c in WALL.raw_rgb])

    def _raw(self, mode: str, rgb: list[float]) -> tuple[float, ...]:
        """REF-RAW, RGB-RAW or COL-CAL from the reflected red, green and blue (LEDs on less LEDs off)."""
        led_off = LED_OFF_ADC - 2.0 * self.ambient
        if mode == "RGB-RAW":
            return (rgb[0], rgb[1], rgb[2], led_off)
        if mode == "REF-RAW":
            return (led_off - rgb[0], led_off)
        return (rgb[0], rgb[1], rgb[2])

    def _cells(self) -> list[tuple[int, int, float]]:
        """(col, row, share of the spot) for the cells under the spot."""
        x, y, _ = self.position()
        floor, h = self.floor, self.half
        size = floor.cell_cm
        return [
            (col, row, wx * wy)
            for col, wx in _overlaps(x - h, x + h, size, floor.width)
            for row, wy in _overlaps(y - h, y + h, size, floor.height)
        ]

    def measure(self, mode: str) -> tuple[float, ...]:
        if mode == "COL-AMBIENT":
            return (self.ambient,)
        if mode == "COL-REFLECT":  # the line followers' mode: summed in place
            x, y, _ = self.position()
            floor, h = self.floor, self.half
            size = floor.cell_cm
            rows = _overlaps(y - h, y + h, size, floor.height)
            table = floor.reflected
            total = 0.0
            for col, wx in _overlaps(x - h, x + h, size, floor.width):  # the order and products of _cells
                for row, wy in rows:
                    total += table[row][col] * (wx * wy)
            return (total,)
        cells = self._cells()
        if mode == "COL-COLOR":
            col, row, _ = max(cells, key=lambda c: c[2])
            return (self.floor.color_id[row][col],)
        table = self.floor.raw_rgb
        return self._raw(
            mode, [sum(table[row][col][i] * share for col, row, share in cells) for i in range(3)]
        )


def _overlaps(lo: float, hi: float, size: float, count: int) -> list[tuple[int, float]]:
    """The cells [i·size, (i+1)·size) that the interval [lo, hi] overlaps, with the share of it in each."""
    first, last = int(lo // size), int(hi // size)
    if first == last:
        return [(min(max(first, 0), count - 1), 1.0)]
    span = hi - lo
    if last == first + 1:  # the usual edge: the spot is smaller than a cell
        split = last * size
        return [(max(first, 0), (split - lo) / span), (min(last, count - 1), (hi - split) / span)]
    return [
        (min(max(i, 0), count - 1), (min(hi, (i + 1) * size) - max(lo, i * size)) / span)
        for i in range(first, last + 1)
    ]
