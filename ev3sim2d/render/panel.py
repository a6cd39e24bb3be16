"""The side panel: the brick's inner life, which a real robot hides.

Simulated time and how the run ended; per robot its LEDs, each sensor's port,
kind, mode and value, each motor's speed, position and state, the LCD when
the program drew on it and the sounds as they play; at the bottom the last
lines the program printed.  What never changes (headings, ports, kinds) is
drawn once into the frame's background; each frame writes only the values.
"""

from __future__ import annotations

from dataclasses import dataclass

import cv2
import numpy as np

from ..devices.motor import STATE_NAMES
from ..results.trace import Trace
from ..world.colors import COLOR_NAMES_BY_ID, EV3_COLORS
from . import palette
from .layout import FrameLayout
from .robot_layer import RobotLook, sensor_device
from .text import Font, draw_text
from .timeline import Timeline

LCD_SIZE = (178, 128)
LCD_BLANK = (70, 72, 76)  # the screen before the program draws on it
LCD_SHARE = 0.2  # of the frame's height, at most, for each robot's screen (half that in a compact panel)
MIN_FONT_PX = 9  # a panel for several robots shrinks its text down to this, at most to 0.6 of its size
PRINTED_ROWS_WANTED = 2  # and does so until this many printed lines fit below the robots, if they can
STATE_PRIORITY = ("stalled", "overloaded", "holding", "running", "ramping")
LED_SIDES = (("L", "led0"), ("R", "led1"))
LED_COLORS = {
    "off": (60, 60, 64),
    "red": (230, 40, 40),
    "green": (40, 200, 70),
    "amber": (255, 176, 0),
    "orange": (255, 120, 0),
    "yellow": (240, 228, 66),
}
_COLOR_SWATCHES = {c.id: palette.bgr(c.display_rgb) for c in EV3_COLORS.values()}


def _text(image: np.ndarray, font: Font, text: str, x: int, y: int, color, align: str = "left") -> int:
    """Text on the panel's background (from the glyph cache)."""
    return draw_text(image, font, text, x, y, color, align, palette.PANEL_BG)


def led_color_name(red: int, green: int) -> str:
    """The colour a brick status LED shows with these red and green brightnesses."""
    if red <= 0 and green <= 0:
        return "off"
    if green <= 0:
        return "red"
    if red <= 0:
        return "green"
    ratio = green / red
    return "orange" if ratio < 0.75 else "yellow" if ratio > 2 else "amber"


def sensor_value_text(kind: str, mode: str, values: list[int]) -> str:
    """A sensor's reading in words and units, from the driver's integers."""
    if not values:
        return "—"
    v = values[0]
    if kind == "touch":
        return "pressed" if v else "released"
    if kind == "color":
        if mode == "COL-COLOR":
            return COLOR_NAMES_BY_ID[v] if 0 <= v < len(COLOR_NAMES_BY_ID) else str(v)
        if mode in ("COL-REFLECT", "COL-AMBIENT"):
            return f"{v} %"
    if kind == "ultrasonic" and mode.startswith(("US-DIST", "US-SI", "US-DC")):
        return f"{v / 10:.1f} {'in' if mode.endswith('-IN') else 'cm'}"
    if kind == "gyro":
        if mode in ("GYRO-ANG", "TILT-ANG"):
            return f"{v}°"
        if mode in ("GYRO-RATE", "GYRO-FAS", "TILT-RATE"):
            return f"{v}°/s"
        if mode == "GYRO-G&A" and len(values) > 1:
            return f"{values[0]}° {values[1]}°/s"
    mode_spec = sensor_device(kind).MODES.get(mode)  # (none for a kind this ev3sim2d does not know)
    if mode_spec is None or mode_spec.decimals == 0:
        text = " ".join(str(x) for x in values)
    else:
        text = " ".join(f"{x / 10**mode_spec.decimals:.{mode_spec.decimals}f}" for x in values)
    units = mode_spec.units if mode_spec else ""
    unit = {"pct": "%", "cm": "cm", "in": "in", "deg": "°"}.get(units, units)  # (a new kind's: as it says)
    return f"{text} {unit}" if unit and len(values) == 1 else text


def motor_state_word(bits: int) -> str:
    """The one word that matters most of a motor's state flags ('stopped' when none is set)."""
    names = {name for bit, name in STATE_NAMES if bits & bit}
    return next((name for name in STATE_PRIORITY if name in names), "stopped")


@dataclass
class _RobotRows:
    """Where one robot's values go (y of each row, in px)."""

    leds_y: int
    sensor_ys: list[int]
    motor_ys: list[int]
    lcd_box: tuple[int, int, int, int] | None  # x, y, w, h
    sound_y: int | None


class Panel:
    """The panel at the right of a video frame."""

    def __init__(
        self, trace: Trace, timeline: Timeline, looks: list[RobotLook], layout: FrameLayout, speed: float
    ):
        self.trace = trace
        self.timeline = timeline
        self.looks = looks
        self.speed = speed
        self.x0, self.x1, self.height = layout.panel_x, layout.width, layout.height
        self.many = len(trace.robots) > 1
        self._lcd_cache: dict[tuple[int, int], np.ndarray] = {}
        self._printed_cache: tuple[int, np.ndarray] | None = None
        # the full layout if every robot's section fits; else compact ones (no column headings), their
        # text ever smaller, until they fit with room for a few printed lines, or at least fit
        candidates = [(False, layout.font_px)]
        if self.many:
            smallest = max(MIN_FONT_PX, int(layout.font_px * 0.6))
            candidates += [(True, px) for px in range(layout.font_px, smallest - 1, -1)]
        fitting = None
        for compact, px in candidates:
            self._plan(compact, px)
            bottom = self.sections[-1][1] if self.sections else 0
            if bottom <= self.height and self.printed_rows >= PRINTED_ROWS_WANTED:
                break
            if fitting is None and bottom <= self.height:
                fitting = (compact, px)
        else:
            if fitting is not None:
                self._plan(*fitting)

    def _fonts(self, px: int) -> None:
        self.font = Font(px)
        self.bold = Font(px, bold=True)
        self.big = Font(int(round(px * 1.7)), bold=True)
        self.pad = max(4, self.font.advance)
        self.row = int(round(self.font.height * 1.2))
        self.left = self.x0 + self.pad
        self.right = self.x1 - self.pad

    # ------------------------------------------------------------ layout
    def col(self, chars: int) -> int:
        """x of a text column, counted in characters from the panel's left margin."""
        return self.left + chars * self.font.advance

    def _plan(self, compact: bool, font_px: int) -> None:
        """Where everything goes, with text of `font_px` and, if `compact`, no column headings."""
        self._fonts(font_px)
        self.compact = compact
        f = self.font
        # motor columns, counted from the right so that they fit any panel of 38 characters or more
        self.state_x = self.right - f.width("overloaded")
        self.position_end = self.state_x - f.advance
        self.speed_end = self.position_end - f.width(" -123456°")
        y = self.pad // 2
        self.title_y = y
        y += self.row
        self.time_y = y
        y += self.big.height + 2
        self.status_y = y
        y += self.row + self.pad // 2
        self.rules = [y]
        y += self.pad // 2
        self.robot_rows: list[_RobotRows] = []
        self.robot_headers: list[int] = []
        self.sections: list[tuple[int, int]] = []  # each robot's part of the panel: top, bottom y
        for i, robot in enumerate(self.trace.robots):
            self.robot_headers.append(y)
            top = y
            leds_y = y
            y += self.row
            if not compact:
                y += self.row  # sensor header
            sensor_ys = []
            for _ in robot["sensors"]:
                sensor_ys.append(y)
                y += self.row
            y += self.row // 3
            if not compact:
                y += self.row  # motor header
            motor_ys = []
            for _ in robot["motors"]:
                motor_ys.append(y)
                y += self.row
            lcd_box = None
            if self.timeline.used_lcd(i):
                share = LCD_SHARE / 2 if compact else LCD_SHARE
                scale = min((self.right - self.left) / LCD_SIZE[0], self.height * share / LCD_SIZE[1])
                if scale >= 1:
                    scale = int(scale)
                w, h = int(LCD_SIZE[0] * scale), int(LCD_SIZE[1] * scale)
                y += self.row // 3
                lcd_box = (self.left + self.font.advance * 5, y, w, h)
                y += h + self.row // 3
            sound_y = None
            if self.timeline.made_sounds(i):
                sound_y = y
                y += self.row
            self.robot_rows.append(_RobotRows(leds_y, sensor_ys, motor_ys, lcd_box, sound_y))
            self.sections.append((top, y))
            y += self.pad // 2
            self.rules.append(y)
            y += self.pad // 2
        self.printed_y = y
        self.printed_rows = max(0, (self.height - self.pad // 2 - (y + self.row)) // self.row)

    # ------------------------------------------------------------ still parts
    def draw_base(self, image: np.ndarray) -> None:
        """Background, headings, ports and kinds: everything that stays the same in every frame."""
        image[:, self.x0 : self.x1] = palette.PANEL_BG
        title = self.trace.world.get("title") or self.trace.world.get("name") or ""
        _text(
            image,
            self.bold,
            self.bold.fit(title, self.right - self.left),
            self.left,
            self.title_y,
            palette.HEADING,
        )
        for y in self.rules:
            if y < self.height:  # a panel too small for everything is cut off at the bottom
                image[y, self.left : self.right] = palette.PANEL_RULE
        f, dim = self.font, palette.TEXT_DIM
        for i, (robot, look, rows) in enumerate(
            zip(self.trace.robots, self.looks, self.robot_rows, strict=True)
        ):
            y = self.robot_headers[i]
            x = self.left
            if self.many:  # its number, as drawn on the robot
                x = _text(image, self.bold, str(i + 1), x, y, palette.HEADING) + f.advance
            sw = f.height - 4
            cv2.rectangle(image, (x, y + 2), (x + sw, y + 2 + sw), look.color, -1)
            cv2.rectangle(image, (x, y + 2), (x + sw, y + 2 + sw), palette.TEXT, 1)
            x += 2 * f.advance  # (the swatch is a little narrower than two characters)
            _text(
                image,
                self.bold,
                self.bold.fit(look.name, self.right - f.width("LEDs L   yellow R   yellow  ") - x),
                x,
                y,
                palette.HEADING,
            )
            if not self.compact:
                _text(image, f, "port kind       mode", self.left, y + self.row, dim)
                _text(image, f, "value", self.right, y + self.row, dim, align="right")
            for (port, kind), sy in zip(robot["sensors"], rows.sensor_ys, strict=True):
                _text(image, f, port, self.left, sy, palette.TEXT)
                _text(image, f, sensor_device(kind).LABEL or kind, self.col(5), sy, palette.TEXT)
            if not self.compact:
                my = rows.motor_ys[0] - self.row if rows.motor_ys else rows.sensor_ys[-1] + self.row
                _text(image, f, "port kind", self.left, my, dim)
                _text(image, f, "speed", self.speed_end, my, dim, align="right")
                _text(image, f, "position", self.position_end, my, dim, align="right")
                _text(image, f, "state", self.state_x, my, dim)
            for (port, kind), ty in zip(robot["motors"], rows.motor_ys, strict=True):
                _text(image, f, port, self.left, ty, palette.TEXT)
                _text(image, f, kind, self.col(5), ty, palette.TEXT)
            if rows.lcd_box is not None:
                x, ly, w, h = rows.lcd_box
                _text(image, f, "LCD", self.left, ly, dim)
                cv2.rectangle(image, (x - 2, ly - 2), (x + w + 1, ly + h + 1), palette.PANEL_RULE, 1)
            if rows.sound_y is not None:
                _text(image, f, "sound", self.left, rows.sound_y, dim)
        if self.printed_rows > 0:
            _text(image, f, "printed", self.left, self.printed_y, dim)

    # ------------------------------------------------------------ each frame
    def draw(self, image: np.ndarray, t_s: float, tick: int) -> None:
        """The values at time t_s (tick: the last tick at or before it)."""
        tl, f = self.timeline, self.font
        _text(image, self.big, f"{t_s:.2f} s", self.left, self.time_y, palette.HEADING)
        x = self.left + self.big.width(f"{tl.end_s:.2f} s")
        extra = f"of {tl.end_s:.2f} s" + (f"  ×{self.speed:g}" if self.speed != 1 else "")
        _text(image, f, extra, x + f.advance, self.time_y + self.big.ascent - f.ascent, palette.TEXT_DIM)
        result = self.trace.result or {}
        if t_s >= tl.end_s - 1e-9 and result.get("reason"):
            color = palette.STATUS_COLORS.get(result.get("status"), palette.TEXT)
            _text(image, f, f.fit(result["reason"], self.right - self.left), self.left, self.status_y, color)
        else:
            _text(image, f, "running", self.left, self.status_y, palette.TEXT_DIM)
        for i, (robot, rows) in enumerate(zip(self.trace.robots, self.robot_rows, strict=True)):
            self._draw_leds(image, i, rows.leds_y, t_s)
            for (port, kind), y in zip(robot["sensors"], rows.sensor_ys, strict=True):
                reading = tl.sensor(i, port, t_s)
                if reading is None:
                    _text(image, f, "—", self.right, y, palette.TEXT_DIM, align="right")
                    continue
                mode, values = reading
                _text(image, f, mode, self.col(16), y, palette.TEXT)
                text = sensor_value_text(kind, mode, values)
                end = self.right
                if kind == "color" and mode == "COL-COLOR" and values and values[0] in _COLOR_SWATCHES:
                    sw = f.height - 6
                    cv2.rectangle(image, (end - sw, y + 3), (end, y + 3 + sw), _COLOR_SWATCHES[values[0]], -1)
                    cv2.rectangle(image, (end - sw, y + 3), (end, y + 3 + sw), palette.TEXT, 1)
                    end -= sw + f.advance
                _text(image, f, text, end, y, palette.HEADING, align="right")
            for (position, speed, state), y in zip(tl.motors(i, tick), rows.motor_ys, strict=True):
                _text(image, f, f"{speed:5.0f}°/s", self.speed_end, y, palette.TEXT, align="right")
                _text(image, f, f"{position:8.0f}°", self.position_end, y, palette.TEXT, align="right")
                word = motor_state_word(state)
                _text(image, f, word, self.state_x, y, palette.STATE_COLORS.get(word, palette.TEXT_DIM))
            if rows.lcd_box is not None:
                self._draw_lcd(image, rows.lcd_box, tl.lcd_frame(i, t_s))
            if rows.sound_y is not None:
                self._draw_sounds(image, i, rows.sound_y, t_s)
        if self.printed_rows > 0:
            self._draw_printed(image, t_s)

    def _draw_leds(self, image: np.ndarray, robot: int, y: int, t_s: float) -> None:
        state = self.timeline.leds(robot, t_s)
        f = self.font
        x = self.right - f.width("LEDs L   yellow R   yellow")
        x = _text(image, f, "LEDs", x, y, palette.TEXT_DIM) + f.advance
        for side, led in LED_SIDES:
            red = int(state.get(f"{led}:red:brick-status", 0))
            green = int(state.get(f"{led}:green:brick-status", 0))
            name = led_color_name(red, green)
            x = _text(image, f, side, x, y, palette.TEXT_DIM) + f.advance // 2
            r = max(3, f.height // 2 - 3)
            centre = (x + r, y + f.height // 2)
            level = max(red, green) / 255 if name != "off" else 1.0
            shade = tuple(int(c * (0.35 + 0.65 * level)) for c in palette.bgr(LED_COLORS[name]))
            cv2.circle(image, centre, r, shade, -1, cv2.LINE_AA)
            cv2.circle(image, centre, r, palette.TEXT_DIM, 1, cv2.LINE_AA)
            _text(image, f, name, x + 2 * r + f.advance // 2, y, palette.TEXT)
            x += 2 * r + f.advance // 2 + f.width("yellow ")

    def _draw_lcd(self, image: np.ndarray, box: tuple[int, int, int, int], frame: int | None) -> None:
        x, y, w, h = box
        if y + h > self.height:
            return
        if frame is None:
            image[y : y + h, x : x + w] = LCD_BLANK
            middle = y + h // 2 - self.font.height // 2
            draw_text(image, self.font, "(blank)", x + w // 2, middle, palette.TEXT_DIM, "center", LCD_BLANK)
            return
        key = (frame, w)
        pixels = self._lcd_cache.get(key)
        if pixels is None:
            grey = np.frombuffer(self.trace.lcd_frames[frame], dtype=np.uint8).reshape(
                LCD_SIZE[1], LCD_SIZE[0]
            )
            method = cv2.INTER_NEAREST if w % LCD_SIZE[0] == 0 else cv2.INTER_AREA
            grey = cv2.resize(grey, (w, h), interpolation=method)
            pixels = cv2.cvtColor(grey, cv2.COLOR_GRAY2BGR)
            if len(self._lcd_cache) > 64:
                self._lcd_cache.clear()
            self._lcd_cache[key] = pixels
        image[y : y + h, x : x + w] = pixels

    def _draw_sounds(self, image: np.ndarray, robot: int, y: int, t_s: float) -> None:
        words = []
        for s in self.timeline.sounds_at(robot, t_s):
            if s.kind == "tone":
                words.append(f"♪ {s.frequency:.0f} Hz")
            elif s.kind == "speech":
                words.append(f"says “{s.text}”")
            else:
                words.append(f"plays {s.text}")
        x = self.col(6)
        if words:
            _text(image, self.font, self.font.fit(", ".join(words), self.right - x), x, y, palette.HEADING)
        else:
            _text(image, self.font, "—", x, y, palette.TEXT_DIM)

    def _draw_printed(self, image: np.ndarray, t_s: float) -> None:
        lines = self.timeline.printed(t_s)
        cached = self._printed_cache
        top = self.printed_y + self.row
        if cached is None or cached[0] != len(lines):
            block = np.empty((self.printed_rows * self.row, self.x1 - self.x0, 3), dtype=np.uint8)
            block[:] = palette.PANEL_BG
            many = self.many
            for k, line in enumerate(lines[-self.printed_rows :]):
                y = k * self.row
                stamp = f"{line.t_s:7.2f}"
                x = _text(block, self.font, stamp, self.pad, y, palette.TEXT_DIM) + self.font.advance
                if many:
                    x = (
                        _text(block, self.font, f"{line.robot + 1}:", x, y, palette.TEXT_DIM)
                        + self.font.advance
                    )
                text = self.font.fit(line.text.replace("\t", "    "), block.shape[1] - self.pad - x)
                _text(
                    block, self.font, text, x, y, palette.STDERR if line.stream == "stderr" else palette.TEXT
                )
            cached = self._printed_cache = (len(lines), block)
        block = cached[1]
        image[top : top + block.shape[0], self.x0 : self.x1] = block[: max(0, self.height - top)]
