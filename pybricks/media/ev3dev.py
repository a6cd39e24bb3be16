"""Sounds, images and fonts of the EV3 (pybricks.media.ev3dev, Pybricks 2.0): SoundFile, ImageFile, Font, Image."""


class SoundFile:
    """The EV3's sound files (bricks/ev3dev/modules/pybricks/media/ev3dev.py)."""


class ImageFile:
    """The EV3's image files (bricks/ev3dev/modules/pybricks/media/ev3dev.py)."""
