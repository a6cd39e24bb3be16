"""Images, fonts and the EV3's screen (pybricks.media.ev3dev Image and Font, EV3Brick().screen).

The firmware draws with the GRX3 library (pybricks-micropython v2.0.0: bricks/ev3dev/
pb_type_ev3dev_image.c and pb_type_ev3dev_font.c).  An Image is a drawing context: one made from
'_screen_' draws straight onto the LCD, so every call shows at once; Image.empty() and Image(file) are
pictures in memory; Image(image, sub=True, ...) draws into a window of another image.  Here the pixels
are a Pillow picture of 8-bit grey that only ever holds black (0) and white (255), as the EV3's
monochrome LCD shows them, and each call that changes the screen sends it to the simulated brick with
`_link.call("display", pixels)` (178 x 128 bytes, row by row), as ev3dev2/display.py does.

Colours (map_color): BLACK is black, WHITE is white, None draws nothing; the other Colors, which GRX
turns into RGB, show black or white by their brightness, as a one-bit screen has them.
"""

import io
import os

from PIL import Image as _PILImage
from PIL import ImageDraw, ImageFont

from . import _link
from ._arguments import get_int
from .parameters import Color

SCREEN_WIDTH = 178
SCREEN_HEIGHT = 128
WHITE = 255
BLACK = 0

# map_color in pb_type_ev3dev_image.c: the web colours GRX is given for each Color
_RGB = {
    "BLACK": (0, 0, 0),
    "BLUE": (0, 0, 255),
    "GREEN": (0, 128, 0),
    "YELLOW": (255, 255, 0),
    "RED": (255, 0, 0),
    "WHITE": (255, 255, 255),
    "BROWN": (165, 42, 42),
    "ORANGE": (255, 165, 0),
    "PURPLE": (128, 0, 128),
}

_HERE = os.path.dirname(os.path.abspath(__file__))
# the project's fonts: beside the shim in a source tree (ev3sim2d/render/fonts), or, in an installed wheel
# where the shim is ev3sim2d/_shim/pybricks, two folders up
_FONT_FOLDERS = [
    os.path.join(os.path.dirname(_HERE), "ev3sim2d", "render", "fonts"),
    os.path.join(os.path.dirname(os.path.dirname(_HERE)), "render", "fonts"),
]


def _read_fonts():
    """The font files' bytes, read when the shim is imported: a brick imports it before its sandbox closes
    (brick/run.py SHIM_MODULES), after which the project's files cannot be read; {} if they cannot."""
    found = {}
    for name in ("DejaVuSansMono.ttf", "DejaVuSansMono-Bold.ttf"):
        for folder in _FONT_FOLDERS:
            try:
                with open(os.path.join(folder, name), "rb") as f:
                    found[name] = f.read()
                break
            except OSError:
                continue
    return found


_FONT_FILES = _read_fonts()
_PIXELS_PER_POINT = 4 / 3  # a size-12 font is 16 px, which makes the default font as tall as the brick's


def grey(color):
    """The grey level (0 or 255) a Color draws with on the EV3's screen, or None for no colour."""
    if color is None:
        return None
    if getattr(color, "_enum", None) != "Color":
        raise TypeError(f"Expected Color, got {type(color).__name__}")
    r, g, b = _RGB[color.name]
    return WHITE if (299 * r + 587 * g + 114 * b) // 1000 >= 128 else BLACK


def _threshold(picture):
    """A picture as the monochrome screen shows it: transparent parts white, then black or white."""
    if picture.mode in ("RGBA", "LA", "PA") or (picture.mode == "P" and "transparency" in picture.info):
        picture = picture.convert("RGBA")
        background = _PILImage.new("RGBA", picture.size, (255, 255, 255, 255))
        picture = _PILImage.alpha_composite(background, picture)
    return picture.convert("L").point(lambda v: WHITE if v >= 128 else BLACK)


class Font:
    """A font to draw text with: Font(family=None, size=12, bold=False, monospace=False, lang=None,
    script=None) (pb_type_ev3dev_font.c ev3dev_Font_make_new).

    The brick's fonts are GRX bitmap fonts (the default one Lucida 12, 19 px tall); here a proportional
    font is Pillow's own sans-serif (Aileron) and a monospace or bold one DejaVu Sans Mono, at 4/3 px a
    point.  `family` says which font is used; `lang` and `script` are checked as on the brick and
    otherwise not used."""

    DEFAULT = None  # (set below: the font every Image starts with)

    def __init__(self, family=None, size=12, bold=False, monospace=False, lang=None, script=None):
        if family is not None and not isinstance(family, str):
            raise TypeError("family must be a str or None")
        if isinstance(size, float) or not isinstance(size, int):
            raise TypeError(f"can't convert {type(size).__name__} to int")
        if lang is not None and not isinstance(lang, str):
            raise TypeError("lang must be a str or None")
        if script is not None:
            if not isinstance(script, str):
                raise TypeError("script must be a str or None")
            if len(script) != 4:
                raise ValueError("script code must have 4 characters")
        pixels = max(int(round(size * _PIXELS_PER_POINT)), 1)
        mono = bool(monospace) or bool(bold) or (family is not None and "mono" in family.lower())
        self._font = None
        if mono:
            name = "DejaVuSansMono-Bold.ttf" if bold else "DejaVuSansMono.ttf"
            if name in _FONT_FILES:
                self._font = ImageFont.truetype(io.BytesIO(_FONT_FILES[name]), pixels)
        if self._font is None:
            self._font = ImageFont.load_default(size=pixels)
        self.family, self.style = self._font.getname()
        ascent, descent = self._font.getmetrics()
        self.height = ascent + descent
        self.width = max(int(round(self._font.getlength(chr(c)))) for c in range(32, 127))

    def text_width(self, text):
        """The width of `text` in pixels."""
        if not isinstance(text, str):
            raise TypeError("can't convert to str implicitly")
        return int(round(self._font.getlength(text)))

    def text_height(self, text):
        """The height of `text` in pixels (the font's height, as GRX gives it)."""
        if not isinstance(text, str):
            raise TypeError("can't convert to str implicitly")
        return self.height

    def __repr__(self):
        return f"<Font {self.family} {self.style}>"


Font.DEFAULT = Font()

_screen_pixels = None  # the LCD's picture, made at the first use of the screen


def _screen():
    global _screen_pixels
    if _screen_pixels is None:
        _screen_pixels = _PILImage.new("L", (SCREEN_WIDTH, SCREEN_HEIGHT), WHITE)
    return _screen_pixels


def _png_path(filename):
    """The firmware adds '.png' to a file name without it (ev3dev_Image_make_new, ev3dev_Image_save)."""
    if not isinstance(filename, str):
        raise TypeError("can't convert to str implicitly")
    if filename.endswith(".png") or filename.endswith(".PNG"):
        return filename
    return filename + ".png"


def _load_png(filename):
    """The picture in a .png file, or for one of ImageFile's pictures of the brick (which ev3sim2d does
    not have) a stand-in: the picture's name in a frame.  OSError as on the brick for anything else."""
    path = _png_path(filename)
    try:
        with _PILImage.open(path) as picture:
            if picture.format != "PNG":
                raise OSError(f"'{path}' is not a .png file")
            return _threshold(picture)
    except (OSError, ValueError, _PILImage.DecompressionBombError) as err:
        from .media.ev3dev import ImageFile

        if path in ImageFile._ALL:
            return _stand_in(path)
        if isinstance(err, OSError) and str(err).startswith("'"):
            raise
        raise OSError(f"'{path}' is not a .png file") from None


def _stand_in(path):
    """A 178 x 128 picture that names a picture of the brick's: 'eyes/angry' in a frame."""
    picture = _PILImage.new("L", (SCREEN_WIDTH, SCREEN_HEIGHT), WHITE)
    draw = ImageDraw.Draw(picture)
    draw.fontmode = "1"
    name = path[len("/usr/share/images/ev3dev/mono/") : -len(".png")]
    draw.rectangle((0, 0, SCREEN_WIDTH - 1, SCREEN_HEIGHT - 1), outline=BLACK)
    font = Font.DEFAULT._font
    width = font.getlength(name)
    draw.text(
        ((SCREEN_WIDTH - width) // 2, (SCREEN_HEIGHT - Font.DEFAULT.height) // 2), name, fill=BLACK, font=font
    )
    return picture


class Image:
    """An image to draw on: Image(source, sub=False, x1=None, y1=None, x2=None, y2=None)
    (pb_type_ev3dev_image.c ev3dev_Image_make_new).

    source: '_screen_' (the EV3's screen), a .png file's name (the extension may be left out), or an
    Image (a copy of it; with sub=True, a window x1, y1 to x2, y2 of it that draws into it)."""

    def __init__(self, source, *, sub=False, x1=None, y1=None, x2=None, y2=None):
        self._left, self._top = 0, 0
        if isinstance(source, str) and source == "_screen_":
            self._pixels = _screen()
            self._on_screen = True
            width, height = SCREEN_WIDTH, SCREEN_HEIGHT
        elif isinstance(source, str):
            self._pixels = _load_png(source)
            self._on_screen = False
            width, height = self._pixels.size
        elif isinstance(source, Image):
            self._on_screen = source._on_screen if sub else False
            if sub:
                left, top = get_int(x1), get_int(y1)
                right, bottom = get_int(x2), get_int(y2)
                # grx_context_new_subcontext: the window, clipped to the image it is in
                left, right = max(min(left, right), 0), min(max(left, right), source.width - 1)
                top, bottom = max(min(top, bottom), 0), min(max(top, bottom), source.height - 1)
                self._pixels = source._pixels
                self._left, self._top = source._left + left, source._top + top
                width, height = max(right - left + 1, 0), max(bottom - top + 1, 0)
            else:
                self._pixels = source._picture().copy()
                width, height = self._pixels.size
        else:
            raise TypeError("Argument must be str or Image")
        self.width = width
        self.height = height
        self._font = Font.DEFAULT
        self._print_x = 0
        self._print_y = 0
        self._buffer = None
        # ev3dev_Image_new: only an image of the screen is cleared, at its first drawing
        self._cleared = not (self._on_screen and not sub)

    @staticmethod
    def empty(width=SCREEN_WIDTH, height=SCREEN_HEIGHT):
        """A new white image, the size of the screen unless told (ev3dev_Image_empty)."""
        width, height = get_int(width), get_int(height)
        if width <= 0 or height <= 0:
            raise ValueError("width and height must be greater than 0")
        return Image(Image._blank(width, height))

    @classmethod
    def _blank(cls, width, height):
        blank = cls.__new__(cls)
        blank._pixels = _PILImage.new("L", (width, height), WHITE)
        blank._left = blank._top = 0
        blank._on_screen = False
        blank.width, blank.height = width, height
        return blank

    # ---------------------------------------------------------------- the pixels
    def _box(self):
        return (self._left, self._top, self._left + self.width, self._top + self.height)

    def _picture(self):
        """This image's pixels, as a picture of its own."""
        if self._box() == (0, 0, *self._pixels.size):
            return self._pixels
        return self._pixels.crop(self._box())

    def _draw(self, how):
        """Draw with how(picture, draw) in this image's coordinates, then show the screen if it is on it."""
        self._clear_once()
        if self.width > 0 and self.height > 0:
            whole = self._box() == (0, 0, *self._pixels.size)
            picture = self._pixels if whole else self._pixels.crop(self._box())
            draw = ImageDraw.Draw(picture)
            draw.fontmode = "1"  # (the brick's fonts are bitmaps: no grey edges)
            how(picture, draw)
            if not whole:
                self._pixels.paste(picture, self._box()[:2])
        self._show()

    def _clear_once(self):
        if not self._cleared:
            self._cleared = True
            self._pixels.paste(WHITE, self._box())

    def _show(self):
        if self._on_screen:
            _link.call("display", self._pixels.tobytes())

    # ---------------------------------------------------------------- drawing
    def clear(self):
        """Make the image all white, and start print() at the top left again."""
        self._cleared = True
        self._pixels.paste(WHITE, self._box())
        self._print_x = self._print_y = 0
        self._show()

    def draw_pixel(self, x, y, color=Color.BLACK):
        """Draw one pixel."""
        x, y, level = get_int(x), get_int(y), grey(color)

        def how(picture, draw):
            if level is not None:
                draw.point((x, y), fill=level)

        self._draw(how)

    def draw_line(self, x1, y1, x2, y2, width=1, color=Color.BLACK):
        """Draw a line from (x1, y1) to (x2, y2), `width` pixels wide."""
        x1, y1, x2, y2, width = get_int(x1), get_int(y1), get_int(x2), get_int(y2), get_int(width)
        level = grey(color)

        def how(picture, draw):
            if level is not None and width > 0:
                draw.line((x1, y1, x2, y2), fill=level, width=width)

        self._draw(how)

    def draw_box(self, x1, y1, x2, y2, r=0, fill=False, color=Color.BLACK):
        """Draw a rectangle with corners (x1, y1) and (x2, y2), with corners rounded by `r`, filled or not."""
        x1, y1, x2, y2, r = get_int(x1), get_int(y1), get_int(x2), get_int(y2), get_int(r)
        level = grey(color)
        box = (min(x1, x2), min(y1, y2), max(x1, x2), max(y1, y2))

        def how(picture, draw):
            if level is None:
                return
            if r > 0:
                draw.rounded_rectangle(box, radius=r, fill=level if fill else None, outline=level)
            else:
                draw.rectangle(box, fill=level if fill else None, outline=level)

        self._draw(how)

    def draw_circle(self, x, y, r, fill=False, color=Color.BLACK):
        """Draw a circle of radius `r` around (x, y), filled or not."""
        x, y, r = get_int(x), get_int(y), abs(get_int(r))
        level = grey(color)

        def how(picture, draw):
            if level is not None:
                draw.ellipse((x - r, y - r, x + r, y + r), fill=level if fill else None, outline=level)

        self._draw(how)

    def draw_image(self, x, y, source, transparent=None):
        """Draw `source` (an Image or a .png file's name) with its top left corner at (x, y); pixels of the
        `transparent` colour are left out."""
        x, y = get_int(x), get_int(y)
        if isinstance(source, str):
            source = Image(source)
        if not isinstance(source, Image):
            raise TypeError("Image object is required")
        level = grey(transparent)
        picture_in = source._picture().copy()

        def how(picture, draw):
            if level is None:
                picture.paste(picture_in, (x, y))
            else:
                mask = picture_in.point(lambda v: 0 if v == level else 255)
                picture.paste(picture_in, (x, y), mask)

        self._draw(how)

    def load_image(self, source):
        """Clear the image and draw `source` (an Image or a .png file's name) in its middle."""
        if isinstance(source, str):
            source = Image(source)
        if not isinstance(source, Image):
            raise TypeError("source must be Image or str")
        x = int((self.width - source.width) / 2)
        y = int((self.height - source.height) / 2)
        if self._on_screen:  # (the brick draws into a buffer first, so the screen does not flicker)
            if self._buffer is None:
                self._buffer = Image.empty(self.width, self.height)
            self._buffer.clear()
            self._buffer.draw_image(x, y, source)
            source, x, y = self._buffer, 0, 0
        else:
            self.clear()
        self.draw_image(x, y, source)

    def draw_text(self, x, y, text, text_color=Color.BLACK, background_color=None):
        """Draw `text` (anything: it is printed as str) with its top left corner at (x, y)."""
        x, y = get_int(x), get_int(y)
        if not isinstance(text, (str, bytes)):
            text = str(text)
        elif isinstance(text, bytes):
            text = text.decode("utf-8", "replace")
        fg, bg = grey(text_color), grey(background_color)
        font = self._font

        def how(picture, draw):
            if bg is not None:
                width = font.text_width(text)
                draw.rectangle((x, y, x + width - 1, y + font.height - 1), fill=bg)
            if fg is not None:
                draw.text((x, y), text, fill=fg, font=font._font)

        self._draw(how)

    def set_font(self, font):
        """Use `font` (a Font) for draw_text() and print()."""
        if not isinstance(font, Font):
            raise TypeError("Requires Font object")
        self._font = font

    def print(self, *args, sep=" ", end="\n"):
        """Print on the image as print() does on a terminal: line after line from the top, the image
        scrolling up when a line would run off its bottom (ev3dev_Image_print)."""
        if not isinstance(sep, str) or not isinstance(end, str):
            raise TypeError("sep and end must be str")
        text = sep.join(str(arg) for arg in args) + end
        font = self._font
        lines = text.split("\n")

        def how(picture, draw):
            for i, line in enumerate(lines):
                if i > 0:
                    self._print_x = 0
                    self._print_y += font.height
                over = self._print_y + font.height - self.height
                if over > 0:
                    moved = picture.crop((0, over, self.width, self.height))
                    picture.paste(WHITE, (0, 0, self.width, self.height))
                    picture.paste(moved, (0, 0))
                    self._print_y -= over
                width = font.text_width(line)
                if width > 0:
                    draw.rectangle(
                        (
                            self._print_x,
                            self._print_y,
                            self._print_x + width - 1,
                            self._print_y + font.height - 1,
                        ),
                        fill=WHITE,
                    )
                draw.text((self._print_x, self._print_y), line, fill=BLACK, font=font._font)
                self._print_x += width

        self._draw(how)

    def save(self, filename):
        """Save the image as a .png file ('.png' is added to a name without it)."""
        path = _png_path(filename)
        try:
            self._picture().save(path, format="PNG")
        except OSError as err:
            raise OSError(f"Failed to save image: Failed to open '{path}'") from err

    def __repr__(self):
        return f"<Image {self.width}x{self.height}>"
