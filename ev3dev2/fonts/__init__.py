"""
Bitmap fonts for the Display (python-ev3dev2 2.1.0).

The real library ships ev3dev's .pil fonts; ev3sim2d bundles none yet, so
``available()`` lists whatever .pil files are in this folder (none) and
``load()`` fails with upstream's message.  Display.text_pixels falls back to
Pillow's default font for a font it cannot find.
"""

import os.path
from glob import glob

try:
    from PIL import ImageFont
except ImportError:  # Pillow is optional in the simulator: without it there are no fonts to load
    ImageFont = None


def available():
    """The names of the available fonts."""
    font_dir = os.path.dirname(__file__)
    names = [os.path.basename(os.path.splitext(f)[0]) for f in glob(os.path.join(font_dir, "*.pil"))]
    return sorted(names)


def load(name):
    """Loads the font ``name`` as a PIL.ImageFont (needs Pillow)."""
    font_dir = os.path.dirname(__file__)
    pil_file = os.path.join(font_dir, f"{name}.pil")
    if not os.path.exists(pil_file):
        raise Exception(
            f'Failed to load font "{name}". '
            + "Check ev3dev.fonts.available() for the list of available fonts"
        )
    return ImageFont.load(pil_file)
