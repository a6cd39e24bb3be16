"""Text on frames in the shipped DejaVu Sans Mono, built from cached glyphs.

Every glyph is rasterised once per font and inked once per colour and
background; a string is its glyphs side by side (the font is monospaced), so a
number that changes every frame costs a few array copies, not a trip through FreeType.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

FONT_DIR = Path(__file__).parent / "fonts"
FONT_FILES = {False: "DejaVuSansMono.ttf", True: "DejaVuSansMono-Bold.ttf"}
_MAX_CACHED_STRINGS = 4000


class Font:
    """One size and weight of the panel font: `advance` px per character, `height` px per line."""

    def __init__(self, size_px: int, bold: bool = False) -> None:
        self.size_px = size_px
        self.face = ImageFont.truetype(str(FONT_DIR / FONT_FILES[bold]), size_px)
        ascent, descent = self.face.getmetrics()
        self.ascent = ascent
        self.height = ascent + descent
        self.advance = max(1, round(self.face.getlength("0")))
        self._glyphs: dict[str, np.ndarray] = {}
        self._inked: dict[tuple, np.ndarray] = {}
        self._strings: dict[tuple, np.ndarray] = {}

    def glyph(self, char: str) -> np.ndarray:
        """The coverage (0..255) of one character cell, `height` × `advance`."""
        found = self._glyphs.get(char)
        if found is None:
            image = Image.new("L", (self.advance, self.height), 0)
            ImageDraw.Draw(image).text((0, 0), char, font=self.face, fill=255)
            found = self._glyphs[char] = np.asarray(image)
        return found

    def mask(self, text: str) -> np.ndarray:
        """The coverage of a whole string, `height` × `advance·len(text)`."""
        return np.hstack([self.glyph(c) for c in text] or [np.zeros((self.height, 0), np.uint8)])

    def patch(self, text: str, color: tuple[int, int, int], background: tuple[int, int, int]) -> np.ndarray:
        """The string in `color` on `background`, as BGR pixels (kept: panels write the same words often)."""
        key = (text, color, background)
        found = self._strings.get(key)
        if found is None:
            if len(self._strings) > _MAX_CACHED_STRINGS:
                self._strings.clear()
            cells = [self._inked_glyph(c, color, background) for c in text]
            found = self._strings[key] = (
                np.hstack(cells) if cells else np.zeros((self.height, 0, 3), np.uint8)
            )
        return found

    def _inked_glyph(self, char: str, color, background) -> np.ndarray:
        key = (char, color, background)
        found = self._inked.get(key)
        if found is None:
            alpha = self.glyph(char)[:, :, None].astype(np.float32) / 255
            ink, paper = np.array(color, np.float32), np.array(background, np.float32)
            found = self._inked[key] = np.round(paper + (ink - paper) * alpha).astype(np.uint8)
        return found

    def width(self, text: str) -> int:
        return self.advance * len(text)

    def fit(self, text: str, width_px: int) -> str:
        """`text`, cut with an ellipsis so that it is at most `width_px` wide."""
        most = max(0, width_px // self.advance)
        return text if len(text) <= most else text[: max(0, most - 1)] + "…"


def blend_mask(image: np.ndarray, mask: np.ndarray, x: int, y: int, color: tuple[int, int, int]) -> None:
    """Paint `color` into `image` through the coverage `mask` placed with its top-left at (x, y), clipped."""
    h, w = mask.shape
    x0, y0 = max(x, 0), max(y, 0)
    x1, y1 = min(x + w, image.shape[1]), min(y + h, image.shape[0])
    if x0 >= x1 or y0 >= y1:
        return
    alpha = mask[y0 - y : y1 - y, x0 - x : x1 - x, None].astype(np.uint16)
    roi = image[y0:y1, x0:x1]
    ink = np.array(color, dtype=np.uint16)
    roi[:] = ((roi * (255 - alpha) + ink * alpha + 127) // 255).astype(np.uint8)


def draw_text(
    image: np.ndarray,
    font: Font,
    text: str,
    x: int,
    y: int,
    color: tuple[int, int, int],
    align: str = "left",
    background: tuple[int, int, int] | None = None,
) -> int:
    """Write `text` with its top at y; `align` left/right/center about x.  Returns the x just after it.

    With a `background` (the flat colour the text sits on) the pixels come from a cache; without,
    the text is blended onto whatever is there.
    """
    if not text:
        return x
    width = font.width(text)
    if align == "right":
        x -= width
    elif align == "center":
        x -= width // 2
    if background is None:
        blend_mask(image, font.mask(text), x, y, color)
    else:
        paste(image, font.patch(text, color, background), x, y)
    return x + width


def paste(image: np.ndarray, pixels: np.ndarray, x: int, y: int) -> None:
    """Copy `pixels` into `image` with their top-left at (x, y), clipped to the image."""
    h, w = pixels.shape[:2]
    x0, y0 = max(x, 0), max(y, 0)
    x1, y1 = min(x + w, image.shape[1]), min(y + h, image.shape[0])
    if x0 < x1 and y0 < y1:
        image[y0:y1, x0:x1] = pixels[y0 - y : y1 - y, x0 - x : x1 - x]


def draw_label(
    image: np.ndarray,
    font: Font,
    text: str,
    x: int,
    y: int,
    color: tuple[int, int, int],
    background: tuple[int, int, int],
    pad: int = 2,
    bounds: tuple[int, int, int, int] | None = None,
) -> tuple[int, int, int, int]:
    """Text on a filled box with its top-left at (x, y), kept inside `bounds` (x0, y0, x1, y1; default the image)."""
    w, h = font.width(text) + 2 * pad, font.height + 2 * pad
    bx0, by0, bx1, by1 = bounds or (0, 0, image.shape[1], image.shape[0])
    x = int(max(min(x, bx1 - w), bx0, 0))
    y = int(max(min(y, by1 - h), by0, 0))
    image[max(y, 0) : y + h, max(x, 0) : x + w] = background
    draw_text(image, font, text, x + pad, y + pad, color, background=background)
    return (x, y, w, h)
