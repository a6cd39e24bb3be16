"""
The EV3's 178x128 LCD (python-ev3dev2 2.1.0), drawn with Pillow when it is installed.

``update()`` sends the picture to the simulated brick with
``_link.call('display', pixels)``: 178 * 128 bytes of 8-bit greyscale, row by
row (0 black, 255 white), or None when Pillow is missing and nothing is drawn.
"""

import ctypes
import logging
import mmap  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import os  # noqa: F401
import sys  # noqa: F401
from struct import pack  # noqa: F401

from ev3dev2 import _link, fonts, get_current_platform, library_load_warning_message  # noqa: F401

log = logging.getLogger(__name__)

try:
    from PIL import Image, ImageDraw
except ImportError:  # Drawing is cosmetic in the simulator: without Pillow it does nothing.
    Image = ImageDraw = None

try:
    import fcntl  # noqa: F401
except ImportError:
    pass

_XRES = 178
_YRES = 128
_BITS_PER_PIXEL = 32  # ev3dev's EV3 framebuffer: one 32-bit word per pixel


class FbMem:
    """
    The framebuffer memory object: on a brick, the LCD's device file, its fixed and
    variable screen info (from fb.h) and the mapped memory.

    The simulated LCD has no framebuffer: the screen info says what an EV3's says
    (178 x 128 pixels, 32 bits each), ``fid`` and ``mmap`` are None, and
    ``Display.update()`` sends the picture to the simulator instead.
    """

    __slots__ = ("fid", "fix_info", "var_info", "mmap")

    FBIOGET_VSCREENINFO = 0x4600
    FBIOGET_FSCREENINFO = 0x4602

    FB_VISUAL_MONO01 = 0
    FB_VISUAL_MONO10 = 1

    class FixScreenInfo(ctypes.Structure):
        """The fb_fix_screeninfo from fb.h."""

        _fields_ = [
            ("id_name", ctypes.c_char * 16),
            ("smem_start", ctypes.c_ulong),
            ("smem_len", ctypes.c_uint32),
            ("type", ctypes.c_uint32),
            ("type_aux", ctypes.c_uint32),
            ("visual", ctypes.c_uint32),
            ("xpanstep", ctypes.c_uint16),
            ("ypanstep", ctypes.c_uint16),
            ("ywrapstep", ctypes.c_uint16),
            ("line_length", ctypes.c_uint32),
            ("mmio_start", ctypes.c_ulong),
            ("mmio_len", ctypes.c_uint32),
            ("accel", ctypes.c_uint32),
            ("reserved", ctypes.c_uint16 * 3),
        ]

    class VarScreenInfo(ctypes.Structure):
        """The fb_var_screeninfo struct from fb.h."""

        class FbBitField(ctypes.Structure):
            """The fb_bitfield struct from fb.h."""

            _fields_ = [
                ("offset", ctypes.c_uint32),
                ("length", ctypes.c_uint32),
                ("msb_right", ctypes.c_uint32),
            ]

            def __str__(self):
                return "%s (offset %s, length %s, msg_right %s)" % (  # noqa: UP031  (upstream's text)
                    self.__class__.__name__,
                    self.offset,
                    self.length,
                    self.msb_right,
                )

        _fields_ = [
            ("xres", ctypes.c_uint32),
            ("yres", ctypes.c_uint32),
            ("xres_virtual", ctypes.c_uint32),
            ("yres_virtual", ctypes.c_uint32),
            ("xoffset", ctypes.c_uint32),
            ("yoffset", ctypes.c_uint32),
            ("bits_per_pixel", ctypes.c_uint32),
            ("grayscale", ctypes.c_uint32),
            ("red", FbBitField),
            ("green", FbBitField),
            ("blue", FbBitField),
            ("transp", FbBitField),
        ]

        def __str__(self):
            return "%sx%s at (%s,%s), bpp %s, grayscale %s, red %s, green %s, blue %s, transp %s" % (  # noqa: UP031
                self.xres,
                self.yres,
                self.xoffset,
                self.yoffset,
                self.bits_per_pixel,
                self.grayscale,
                self.red,
                self.green,
                self.blue,
                self.transp,
            )

    def __init__(self, fbdev=None):
        """The EV3 LCD's screen info; ``fbdev`` (a device file on a brick) is ignored."""
        if not _link.connected():
            raise _link.NotInSimulation(_link.OUTSIDE_MESSAGE)
        line_length = _XRES * _BITS_PER_PIXEL // 8
        self.fid = None
        self.fix_info = FbMem.FixScreenInfo(smem_len=line_length * _YRES, line_length=line_length)
        self.var_info = FbMem.VarScreenInfo(
            xres=_XRES, yres=_YRES, xres_virtual=_XRES, yres_virtual=_YRES, bits_per_pixel=_BITS_PER_PIXEL
        )
        self.mmap = None


class _NoCanvas:
    """Stands for PIL's ImageDraw when Pillow is missing: every drawing call does nothing."""

    def __getattr__(self, name):
        return lambda *args, **kwargs: None


class Display(FbMem):
    """
    The LCD, with drawing functions from the Python Imaging Library (PIL):
    draw on ``draw`` or ``image``, then call ``update()`` to show it.
    """

    GRID_COLUMNS = 22
    GRID_COLUMN_PIXELS = 8
    GRID_ROWS = 12
    GRID_ROW_PIXELS = 10

    def __init__(self, desc="Display"):
        FbMem.__init__(self)
        self.platform = get_current_platform()

        if Image is not None:
            self._img = Image.new("L", (_XRES, _YRES), "white")
            self._draw = ImageDraw.Draw(self._img)
        else:
            self._img = None
            self._draw = _NoCanvas()
        self.desc = desc

    def __str__(self):
        return self.desc

    @property
    def xres(self):
        """Horizontal screen resolution"""
        return self.var_info.xres

    @property
    def yres(self):
        """Vertical screen resolution"""
        return self.var_info.yres

    @property
    def shape(self):
        """Dimensions of the screen."""
        return (self.xres, self.yres)

    @property
    def draw(self):
        """
        The PIL.ImageDraw.Draw of the screen, e.g.
        ``screen.draw.rectangle((10, 10, 60, 20), fill='black')``.
        """
        return self._draw

    @property
    def image(self):
        """
        The PIL.Image behind the screen (None without Pillow), e.g.
        ``screen.image.paste(picture, (0, 0))``.
        """
        return self._img

    def clear(self):
        """Clears the screen"""
        self._draw.rectangle(((0, 0), self.shape), fill="white")

    def update(self):
        """Shows the pending changes: nothing is drawn on the screen until this is called."""
        pixels = self._img.tobytes() if self._img is not None else None
        _link.call("display", pixels)

    def image_filename(self, filename, clear_screen=True, x1=0, y1=0, x2=None, y2=None):
        if clear_screen:
            self.clear()

        if self._img is None:
            return None

        filename_im = Image.open(filename)

        if x2 is not None and y2 is not None:
            return self._img.paste(filename_im, (x1, y1, x2, y2))
        else:
            return self._img.paste(filename_im, (x1, y1))

    def line(self, clear_screen=True, x1=10, y1=10, x2=50, y2=50, line_color="black", width=1):
        """Draw a line from (x1, y1) to (x2, y2)."""
        if clear_screen:
            self.clear()

        return self.draw.line((x1, y1, x2, y2), fill=line_color, width=width)

    def circle(self, clear_screen=True, x=50, y=50, radius=40, fill_color="black", outline_color="black"):
        """Draw a circle of ``radius`` centred at (x, y)."""
        if clear_screen:
            self.clear()

        x1 = x - radius
        y1 = y - radius
        x2 = x + radius
        y2 = y + radius

        return self.draw.ellipse((x1, y1, x2, y2), fill=fill_color, outline=outline_color)

    def rectangle(
        self, clear_screen=True, x1=10, y1=10, x2=80, y2=40, fill_color="black", outline_color="black"
    ):
        """Draw a rectangle with top left corner (x1, y1) and bottom right corner (x2, y2)."""
        if clear_screen:
            self.clear()

        return self.draw.rectangle((x1, y1, x2, y2), fill=fill_color, outline=outline_color)

    def point(self, clear_screen=True, x=10, y=10, point_color="black"):
        """Draw a single pixel at (x, y)."""
        if clear_screen:
            self.clear()

        return self.draw.point((x, y), fill=point_color)

    def text_pixels(self, text, clear_screen=True, x=0, y=0, text_color="black", font=None):
        """
        Display ``text`` starting at pixel (x, y); (0, 0) is the top left
        corner, (89, 64) the middle.  ``text_color`` is an HTML colour name;
        ``font`` a font name (see ev3dev2.fonts) or a loaded font.  A font
        name that is not bundled falls back to Pillow's default font.
        """
        if clear_screen:
            self.clear()

        if font is not None:
            if isinstance(font, str):
                if font in fonts.available():
                    font = fonts.load(font)
                else:
                    log.warning("font %s is not bundled with ev3sim2d; using the default font", font)
                    font = None
        if font is not None:
            return self.draw.text((x, y), text, fill=text_color, font=font)
        else:
            return self.draw.text((x, y), text, fill=text_color)

    def text_grid(self, text, clear_screen=True, x=0, y=0, text_color="black", font=None):
        """
        Display ``text`` starting at grid cell (x, y) of a 22 x 12 grid of
        8 x 10 pixel cells; ``text_color`` and ``font`` as in text_pixels.
        """
        assert 0 <= x < Display.GRID_COLUMNS, (
            f"grid columns must be between 0 and {Display.GRID_COLUMNS - 1}, {int(x)} was requested"
        )

        assert 0 <= y < Display.GRID_ROWS, (
            f"grid rows must be between 0 and {Display.GRID_ROWS - 1}, {int(y)} was requested"
        )

        return self.text_pixels(
            text, clear_screen, x * Display.GRID_COLUMN_PIXELS, y * Display.GRID_ROW_PIXELS, text_color, font
        )

    def reset_screen(self):
        self.clear()
        self.update()
