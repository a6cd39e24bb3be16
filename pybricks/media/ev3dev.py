"""Sounds, images and fonts of the EV3 (pybricks.media.ev3dev, Pybricks 2.0): SoundFile, ImageFile, Font, Image.

pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/media/ev3dev.py: SoundFile and ImageFile
name the files of the EV3 MicroPython image (/usr/share/sounds/ev3dev/..., /usr/share/images/ev3dev/
mono/...); Font and Image are written in C (extmod/modmedia_ev3dev.c).  The simulated brick has not
those files: playing one of the sound files plays a sound of a second (captioned with its name), and
showing one of the pictures shows its name in a frame.
"""

from .._image import Font, Image
from .._media_files import ImageFile, SoundFile

__all__ = ["SoundFile", "ImageFile", "Font", "Image"]
