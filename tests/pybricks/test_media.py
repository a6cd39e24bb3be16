"""pybricks.media.ev3dev: SoundFile and ImageFile name the brick's files, Font and Image draw as the firmware's.

Firmware: pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/media/ev3dev.py (SoundFile,
ImageFile), bricks/ev3dev/pb_type_ev3dev_image.c (Image) and pb_type_ev3dev_font.c (Font), and its own
tests of them (tests/ev3dev/media/image.py, font.py and their .exp).  Images in memory draw the same
inside and outside a run, so most of these draw outside one; the screen's are in test_brick.py.
"""

import numpy as np
import pytest

from pybricks.media.ev3dev import Font, Image, ImageFile, SoundFile
from pybricks.parameters import Color


def pixels(image) -> np.ndarray:
    return np.asarray(image._picture())


def constants(cls) -> dict:
    return {name: value for name, value in vars(cls).items() if name.isupper() and not name.startswith("_")}


def test_sound_and_image_files_are_the_firmwares():
    """media/ev3dev.py: 105 SoundFiles under /usr/share/sounds/ev3dev/ and 45 ImageFiles under
    /usr/share/images/ev3dev/mono/, named by folder and file (t-rex_roar, okey-dokey and uh-oh keep their
    dashes); pybricks.parameters has both, for 1.0 programs (parameters.py)."""
    sounds, images = constants(SoundFile), constants(ImageFile)
    assert len(sounds) == 105 and len(images) == 45
    assert SoundFile.HELLO == "/usr/share/sounds/ev3dev/communication/hello.wav"
    assert SoundFile.T_REX_ROAR == "/usr/share/sounds/ev3dev/animals/t-rex_roar.wav"
    assert SoundFile.OKEY_DOKEY == "/usr/share/sounds/ev3dev/communication/okey-dokey.wav"
    assert SoundFile.UH_OH == "/usr/share/sounds/ev3dev/expressions/uh-oh.wav"
    assert SoundFile.READY == "/usr/share/sounds/ev3dev/system/ready.wav"
    assert SoundFile.ZERO == "/usr/share/sounds/ev3dev/numbers/zero.wav"
    assert ImageFile.ANGRY == "/usr/share/images/ev3dev/mono/eyes/angry.png"
    assert ImageFile.EV3_ICON == "/usr/share/images/ev3dev/mono/lego/ev3_icon.png"
    assert ImageFile.TARGET == "/usr/share/images/ev3dev/mono/objects/target.png"
    assert all(v.startswith("/usr/share/sounds/ev3dev/") and v.endswith(".wav") for v in sounds.values())
    from pybricks import parameters

    assert parameters.SoundFile is SoundFile and parameters.ImageFile is ImageFile


def test_font_arguments_and_metrics():
    """pb_type_ev3dev_font.c: Font(family=None, size=12, bold=False, monospace=False, lang=None,
    script=None), every argument optional, script a 4-letter code (else ValueError); family, style, width,
    height, text_width(), text_height().  The brick's default is Lucida 12, 19 px tall and 'test' 30 px
    wide (tests/ev3dev/media/font.py.exp); ours is near that."""
    default = Font.DEFAULT
    assert 17 <= default.height <= 21 and 26 <= default.text_width("test") <= 34
    assert default.text_height("test") == default.height
    Font(None, 12, False, False, None, "Latn")
    Font(family="sans-serif", size=12, bold=False, monospace=False, lang="en-US", script=None)
    with pytest.raises(ValueError, match="script code must have 4 characters"):
        Font(script="bad")
    big, mono = Font(size=24), Font(monospace=True)
    assert big.height > default.height
    assert mono.text_width("iiii") == mono.text_width("MMMM")


def test_image_empty_sub_images_and_copies():
    """pb_type_ev3dev_image.c: Image.empty(width, height) is white, screen-sized by default, and >0 in each
    direction (ValueError); Image(img, sub=True, x1, y1, x2, y2) is a window (x2 - x1 + 1 wide: 11 x 11 for
    10..20) that draws into img (grx_context_new_subcontext); Image(img) is a copy (bit_blt)."""
    img = Image.empty(160, 120)
    assert (img.width, img.height) == (160, 120)
    assert (Image.empty().width, Image.empty().height) == (178, 128)
    assert (pixels(img) == 255).all()
    with pytest.raises(ValueError):
        Image.empty(0, 10)
    sub = Image(img, sub=True, x1=10, y1=10, x2=20, y2=20)
    assert (sub.width, sub.height) == (11, 11)
    copy = Image(img)
    sub.draw_box(0, 0, 100, 100, fill=True)  # (clipped to the window)
    whole = pixels(img)
    assert (whole[10:21, 10:21] == 0).all() and (whole == 0).sum() == 121
    assert (pixels(copy) == 255).all()
    with pytest.raises(TypeError):
        Image(5)


def test_draw_image_with_a_transparent_colour():
    """pb_type_ev3dev_image.c ev3dev_Image_draw_image: source drawn with its top left at (x, y); pixels of
    the `transparent` colour are not drawn (grx_color_to_image_mode), none given: all are."""
    stamp = Image.empty(4, 4)
    stamp.draw_pixel(0, 0)
    target = Image.empty(10, 10)
    target.draw_box(0, 0, 9, 9, fill=True)
    target.draw_image(2, 2, stamp, transparent=Color.WHITE)
    assert (pixels(target) == 0).all()
    target.draw_image(2, 2, stamp)
    assert (pixels(target) == 255).sum() == 15 and pixels(target)[2, 2] == 0


def test_save_and_load_a_png(tmp_path):
    """pb_type_ev3dev_image.c ev3dev_Image_save and make_new: '.png' is added to a name without it; a file
    that is not a .png is OSError("'name.png' is not a .png file") (tests/ev3dev/media/image.py.exp);
    load_image(source) clears and centres it."""
    img = Image.empty(30, 20)
    img.draw_circle(15, 10, 5, fill=True)
    img.save(str(tmp_path / "dot"))
    assert (tmp_path / "dot.png").exists()
    again = Image(str(tmp_path / "dot"))
    assert (again.width, again.height) == (30, 20) and (pixels(again) == pixels(img)).all()
    with pytest.raises(OSError, match=r"^'bad\.png' is not a \.png file$"):
        Image("bad.png")
    frame = Image.empty(50, 40)
    frame.draw_box(0, 0, 49, 39, fill=True)
    frame.load_image(again)
    assert (pixels(frame)[10:30, 10:40] == pixels(img)).all() and (pixels(frame)[:10] == 255).all()
    with pytest.raises(TypeError, match="source must be Image or str"):
        frame.load_image(0)


def test_draw_text_and_print_with_a_font():
    """pb_type_ev3dev_image.c draw_text: the text's top left at (x, y), background_color fills the text's
    box (text_width x font height); set_font needs a Font (TypeError 'Requires Font object'); print()
    starts at the top left and clear() brings it back there."""
    img = Image.empty(100, 60)
    img.draw_text(10, 10, "Ab", background_color=Color.BLACK, text_color=Color.WHITE)
    width, height = Font.DEFAULT.text_width("Ab"), Font.DEFAULT.height
    box = pixels(img)[10 : 10 + height, 10 : 10 + width]
    assert (box == 0).sum() > (box == 255).sum() > 0
    assert (pixels(img)[10 + height :] == 255).all()
    with pytest.raises(TypeError, match="Requires Font object"):
        img.set_font("big")
    img.set_font(Font(size=6))
    img.clear()
    img.print("x")
    assert (pixels(img)[: Font(size=6).height] == 0).any() and (
        pixels(img)[Font(size=6).height :] == 255
    ).all()


def test_image_files_of_the_brick_show_their_name(run):
    """media/ev3dev.py ImageFile names pictures of the EV3 MicroPython image, which the simulator has not:
    screen.load_image(ImageFile.ANGRY) shows a 178 x 128 stand-in, the picture's name in a frame, as
    Image(ImageFile.X) is one (ev3dev_Image_load_image)."""
    result = run(
        """
        from pybricks.hubs import EV3Brick
        from pybricks.media.ev3dev import Image, ImageFile
        ev3 = EV3Brick()
        ev3.screen.load_image(ImageFile.ANGRY)
        print(Image(ImageFile.EV3).width, Image(ImageFile.EV3).height)
        """
    )
    assert result.status == "finished", result.error
    assert [line.text for line in result.trace.output] == ["178 128"]
    lcd = np.frombuffer(result.trace.lcd_frames[-1], dtype=np.uint8).reshape(128, 178)
    assert (lcd[0] == 0).all() and (lcd[:, 0] == 0).all() and (lcd[50:80, 40:140] == 0).any()
