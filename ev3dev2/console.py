"""
The EV3 LCD text console (python-ev3dev2 2.1.0), kept as a grid of characters.

On a real EV3 the console is drawn by the terminal from ANSI escape codes.
Here the text is kept in ``lines`` (one string per row) rather than printed,
so the escape codes do not clutter the program's output, and each change is
drawn on the simulated LCD (``_link.call('display', pixels)``, as Display.update).
"""

import os  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import re

from ev3dev2 import _link

try:
    from PIL import Image, ImageDraw, ImageFont
except ImportError:  # without Pillow the console is not drawn
    Image = None

_XRES = 178
_YRES = 128


class Console:
    """
    The EV3 LCD console: text at grid positions, with fonts from
    ``/usr/share/consolefonts/`` (their size sets the grid).
    """

    def __init__(self, font="Lat15-TerminusBold24x12"):
        """``font``: console font name, e.g. ``Lat15-TerminusBold24x12`` (24 x 12 pixel characters)."""
        self._font = None
        self._columns = 0
        self._rows = 0
        self._echo = False
        self._cursor = False
        self.lines = []
        self._position = (1, 1)
        self.set_font(font, reset_console=False)  # don't reset the screen during construction
        self.cursor = False
        self.echo = False

    @property
    def columns(self):
        """The number of columns of the console with the current font."""
        return self._columns

    @property
    def rows(self):
        """The number of rows of the console with the current font."""
        return self._rows

    @property
    def echo(self):
        """Whether the console echoes key presses."""
        return self._echo

    @echo.setter
    def echo(self, value):
        self._echo = value

    @property
    def cursor(self):
        """Whether the console cursor is visible."""
        return self._cursor

    @cursor.setter
    def cursor(self, value):
        self._cursor = value

    def text_at(self, text, column=1, row=1, reset_console=False, inverse=False, alignment="L"):
        """
        Display ``text`` at grid position (``column``, ``row``), 1-based; with
        ``alignment`` ``L`` the text starts there, ``R`` ends there, ``C`` is
        centred there.  ``inverse`` shows white on black; ``reset_console``
        clears the console first.
        """
        if reset_console:
            self.reset_console()

        if alignment == "R":
            column = column - len(text) + 1
        elif alignment == "C":
            column -= len(text) // 2

        self._put(text, column, row)
        self._show()

    def set_font(self, font="Lat15-TerminusBold24x12", reset_console=True):
        """Set the console font (its character size sets rows and columns); optionally reset the console."""
        if font is not None and font != self._font:
            self._font = font
            size = re.search(r"(\d+)x(\d+)$", font)
            height, width = (int(size.group(1)), int(size.group(2))) if size else (24, 12)
            self._rows = _YRES // height
            self._columns = _XRES // width
            self.lines = [""] * self._rows

        if reset_console:
            self.reset_console()

    def clear_to_eol(self, column=None, row=None):
        """Clear to the end of the line from (``column``, ``row``), by default the cursor's position."""
        if column is None or row is None:
            column, row = self._position
        if 1 <= row <= len(self.lines):
            self.lines[row - 1] = self.lines[row - 1][: max(column - 1, 0)]
        self._show()

    def reset_console(self):
        """Clear the console and move the cursor to 1,1."""
        self.lines = [""] * self._rows
        self._position = (1, 1)
        self._show()

    def _put(self, text, column, row):
        """Write ``text`` from (column, row), wrapping at the right edge."""
        column = max(column, 1)
        for char in text:
            if column > self._columns:
                column = 1
                row += 1
            if 1 <= row <= len(self.lines):
                line = self.lines[row - 1].ljust(column - 1)
                self.lines[row - 1] = line[: column - 1] + char + line[column:]
            column += 1
        self._position = (column, row)

    def _show(self):
        """Draw the text on the simulated LCD (black on white, one grid row per line)."""
        if Image is None or not _link.connected() or not self._rows:
            return
        image = Image.new("L", (_XRES, _YRES), 255)
        draw = ImageDraw.Draw(image)
        font = ImageFont.load_default()
        row_height = _YRES // self._rows
        for i, line in enumerate(self.lines):
            draw.text((1, i * row_height + max(row_height - 11, 0) // 2), line, fill=0, font=font)
        _link.call("display", image.tobytes())
