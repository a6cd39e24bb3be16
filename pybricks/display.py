"""EV3 MicroPython 1.0's display: Display('EV3') (pybricks.display, kept in Pybricks 2.0 for 1.0 programs).

pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/display.py and uev3dev/display.py: the 1.0
display draws in a frame buffer of its own (not the 2.0 screen's), and writes all of it to the LCD after
each call.  text() writes with MicroPython's 8 x 8 font, its top 7 pixels above `location`'s y, each text
without a location 8 pixels below the last, the screen scrolling up 8 pixels at the bottom; image() draws
a picture's black pixels (white ones are see-through), at a location or by an Align.
"""

from PIL import Image as _PILImage
from PIL import ImageDraw, ImageFont

from . import _image, _link
from .parameters import Align

_font = ImageFont.load_default_imagefont()  # (a bitmap font as small as MicroPython's: 6 x 11 pixels)


class _Picture:
    """A picture file as 1.0 loads it (uev3dev/display.py ImageFile): any format, black and white."""

    def __init__(self, file_name):
        from .media.ev3dev import ImageFile

        try:
            with _PILImage.open(file_name) as picture:
                self.pixels = _image._threshold(picture)
        except (OSError, ValueError):
            if file_name not in ImageFile._ALL:
                raise OSError(f"unable to open image '{file_name}': No such file or directory") from None
            self.pixels = _image._stand_in(file_name)
        self.width, self.height = self.pixels.size


class Display:
    """Show images or text on a display."""

    _valid_devices = ["EV3"]
    _font_height = 8

    def __init__(self, device_type):
        assert device_type in self._valid_devices, "Selected device is not supported."
        self._pixels = _PILImage.new("L", (_image.SCREEN_WIDTH, _image.SCREEN_HEIGHT), _image.WHITE)
        self._loaded_files = {}
        self._reset_text_history()
        self.clear()

    def _reset_text_history(self):
        self._prev_text_location = (0, 0)

    def _update(self):
        _link.call("display", self._pixels.tobytes())

    def _next_line(self):
        x_prev, y_prev = self._prev_text_location
        y_next = y_prev + self._font_height
        if y_next >= _image.SCREEN_HEIGHT:
            # framebuf.scroll(0, -8): everything moves up; the bottom rows keep what they had
            moved = self._pixels.crop((0, 8, _image.SCREEN_WIDTH, _image.SCREEN_HEIGHT))
            self._pixels.paste(moved, (0, 0))
            self._update()
            return (x_prev, y_prev)
        return (x_prev, y_next)

    def clear(self):
        """Clear everything on the screen."""
        self._pixels.paste(_image.WHITE, (0, 0, _image.SCREEN_WIDTH, _image.SCREEN_HEIGHT))
        self._update()
        self._reset_text_history()

    def text(self, text, location=None):
        """Write text on the screen at location (x, y), or on the next line."""
        if isinstance(location, tuple) and len(location) == 2:
            x, y = location
        else:
            x, y = self._next_line()
        draw = ImageDraw.Draw(self._pixels)
        draw.fontmode = "1"
        draw.text((x, y - 7), str(text), fill=_image.BLACK, font=_font)
        self._update()
        self._prev_text_location = (x, y)

    def image(self, file_name, location_or_alignment=Align.CENTER, clear=True):
        """Show an image file on the display, at an (x, y) location or placed by an Align."""
        if file_name not in self._loaded_files:
            self._loaded_files[file_name] = _Picture(file_name)
        picture = self._loaded_files[file_name]
        width, height = picture.width, picture.height
        screen_w, screen_h = _image.SCREEN_WIDTH, _image.SCREEN_HEIGHT
        if isinstance(location_or_alignment, tuple) and len(location_or_alignment) == 2:
            x, y = location_or_alignment
        else:
            align = location_or_alignment
            assert Align.BOTTOM_LEFT <= align <= Align.TOP_RIGHT, "Invalid location."
            if align in [Align.LEFT, Align.BOTTOM_LEFT, Align.TOP_LEFT]:
                x = 0
            elif align in [Align.RIGHT, Align.BOTTOM_RIGHT, Align.TOP_RIGHT]:
                x = screen_w - width
            else:
                x = (screen_w - width) // 2
            if align in [Align.TOP, Align.TOP_LEFT, Align.TOP_RIGHT]:
                y = 0
            elif align in [Align.BOTTOM, Align.BOTTOM_LEFT, Align.BOTTOM_RIGHT]:
                y = screen_h - height
            else:
                y = (screen_h - height) // 2
        if clear:
            self._pixels.paste(_image.WHITE, (0, 0, screen_w, screen_h))
        black = picture.pixels.point(lambda v: 255 if v == _image.BLACK else 0)
        self._pixels.paste(_image.BLACK, (x, y, x + width, y + height), black)
        self._update()
