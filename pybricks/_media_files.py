"""The EV3's sound and picture files by name: SoundFile and ImageFile (pybricks.media.ev3dev, Pybricks 2.0).

pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/media/ev3dev.py: they name the files of the
EV3 MicroPython image (/usr/share/sounds/ev3dev/..., /usr/share/images/ev3dev/mono/...).  Kept apart from
Font and Image (_image.py) because pybricks.parameters hands them on too, as EV3 MicroPython 1.0 did,
and _image.py needs pybricks.parameters.
"""

_SOUNDS = {
    "animals": "CAT_PURR DOG_BARK_1 DOG_BARK_2 DOG_GROWL DOG_SNIFF DOG_WHINE ELEPHANT_CALL INSECT_BUZZ_1 "
    "INSECT_BUZZ_2 INSECT_CHIRP SNAKE_HISS SNAKE_RATTLE T_REX_ROAR",
    "colors": "BLACK BLUE BROWN GREEN RED WHITE YELLOW",
    "communication": "BRAVO EV3 FANTASTIC GAME_OVER GO GOOD GOOD_JOB GOODBYE HELLO HI LEGO MINDSTORMS MORNING "
    "NO OKAY OKEY_DOKEY SORRY THANK_YOU YES",
    "expressions": "BOING BOO CHEERING CRUNCHING CRYING FANFARE KUNG_FU LAUGHING_1 LAUGHING_2 MAGIC_WAND OUCH "
    "SHOUTING SMACK SNEEZING SNORING UH_OH",
    "information": "ACTIVATE ANALYZE BACKWARDS COLOR DETECTED DOWN ERROR ERROR_ALARM FLASHING FORWARD LEFT "
    "OBJECT RIGHT SEARCHING START STOP TOUCH TURN UP",
    "mechanical": "AIR_RELEASE AIRBRAKE BACKING_ALERT HORN_1 HORN_2 LASER MOTOR_IDLE MOTOR_START MOTOR_STOP "
    "RATCHET SONAR TICK_TACK",
    "movements": "SPEED_DOWN SPEED_IDLE SPEED_UP",
    "numbers": "ZERO ONE TWO THREE FOUR FIVE SIX SEVEN EIGHT NINE TEN",
    "system": "CLICK CONFIRM GENERAL_ALERT OVERPOWER READY",
}
_IMAGES = {
    "eyes": "ANGRY AWAKE BLACK_EYE BOTTOM_LEFT BOTTOM_RIGHT CRAZY_1 CRAZY_2 DISAPPOINTED DIZZY DOWN EVIL HURT "
    "KNOCKED_OUT LOVE MIDDLE_LEFT MIDDLE_RIGHT NEUTRAL NUCLEAR PINCHED_LEFT PINCHED_MIDDLE PINCHED_RIGHT "
    "SLEEPING TEAR TIRED_LEFT TIRED_MIDDLE TIRED_RIGHT TOXIC UP WINKING",
    "information": "ACCEPT BACKWARD DECLINE FORWARD LEFT NO_GO QUESTION_MARK RIGHT STOP_1 STOP_2 THUMBS_DOWN "
    "THUMBS_UP WARNING",
    "lego": "EV3 EV3_ICON",
    "objects": "TARGET",
}
_FILE_NAMES = {"T_REX_ROAR": "t-rex_roar", "OKEY_DOKEY": "okey-dokey", "UH_OH": "uh-oh"}  # (not name.lower())


def _files(cls, folders, extension):
    cls._ALL = set()
    for folder, names in folders.items():
        for name in names.split():
            path = f"{cls._BASE_PATH}{folder}/{_FILE_NAMES.get(name, name.lower())}{extension}"
            setattr(cls, name, path)
            cls._ALL.add(path)
    return cls


class SoundFile:
    """The EV3's sound files: paths to give EV3Brick().speaker.play_file()."""

    _BASE_PATH = "/usr/share/sounds/ev3dev/"


class ImageFile:
    """The EV3's pictures: paths to give Image(), screen.load_image() or draw_image()."""

    _BASE_PATH = "/usr/share/images/ev3dev/mono/"


_files(SoundFile, _SOUNDS, ".wav")
_files(ImageFile, _IMAGES, ".png")
