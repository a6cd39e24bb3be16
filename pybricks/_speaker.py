"""The EV3's speaker (EV3Brick().speaker), as Pybricks 2.0 drives it (pybricks-micropython v2.0.0,
bricks/ev3dev/pb_type_ev3dev_speaker.c).

On a brick, beeps and notes are tones of the kernel's beep device, files are played with `aplay` and
speech with `espeak`, and volumes are set with `amixer`; every method blocks until its sound has ended.
Here each sound is a `_link.call("sound", kind, details)` as ev3dev2/sound.py makes them ('beep' with
its notes, 'play_file', 'speak', 'set_volume'), and the program then sleeps (virtual time) for as long
as the sound lasts.  The mixer has two channels, Beep and PCM (30 % and 70 % when the speaker is first
made); the simulated brick has one volume, so before a tone its volume is set to the Beep channel's and
before a file or speech to the PCM channel's, when it differs.
"""

import os
import re
import time
import wave

from . import _link
from ._arguments import get_int

# pb_type_ev3dev_speaker.c ev3dev_Speaker_play_note: the notes of octave 0, by name
_NOTES = {
    "C": {"": 16.35, "#": 17.32, "b": None},
    "D": {"": 18.35, "#": 19.45, "b": 17.32},
    "E": {"": 20.60, "#": None, "b": 19.45},
    "F": {"": 21.83, "#": 23.12, "b": None},
    "G": {"": 24.50, "#": 25.96, "b": 23.12},
    "A": {"": 27.50, "#": 29.14, "b": 25.96},
    "B": {"": 30.87, "#": None, "b": 29.14},
}

ESPEAK_WPM = 175  # espeak's words per minute at speed 175; the firmware asks for 130
SOUND_FILE_S = 1.0  # how long one of the brick's own sound files (SoundFile) lasts here
APLAY_RAW_BYTES_PER_S = 8000  # aplay plays a file that is not a .wav as 8-bit mono at 8000 Hz

# the mixer: percent per channel, and what the simulated brick's one volume was last set to
_mixer = {"Beep": 30, "PCM": 70, "sent": None}


def _c_div(a, b):
    """C's integer division (toward zero), as the firmware computes note lengths."""
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


def _channel(name):
    """Set the simulated brick's volume to a mixer channel's, if it is not that already."""
    pct = _mixer[name]
    if _mixer["sent"] != pct:
        _link.call("sound", "set_volume", {"pct": pct, "channel": name})
        _mixer["sent"] = pct


def set_channel_volume(channel, volume):
    """Set the Beep or PCM channel (as amixer does) to `volume` percent, 0 to 100."""
    _mixer[channel] = max(0, min(100, volume))


def tone(frequency, duration_ms):
    """Sound a tone of `frequency` Hz for `duration_ms` ms and wait for it to end."""
    _channel("Beep")
    seconds = max(duration_ms, 0) / 1000
    note = {"frequency": frequency, "length_ms": max(duration_ms, 0), "delay_ms": 0, "repeats": 1}
    _link.call("sound", "beep", {"notes": [note], "duration": seconds})
    if seconds > 0:
        time.sleep(seconds)


def wav_seconds(path):
    """How long aplay plays the file at `path`: a .wav file by its frames, another file as raw 8 kHz bytes;
    None if there is no such file."""
    try:
        with wave.open(path, "rb") as wav:
            return wav.getnframes() / float(wav.getframerate())
    except (OSError, EOFError, wave.Error, ZeroDivisionError):
        pass
    try:
        return os.path.getsize(path) / APLAY_RAW_BYTES_PER_S
    except OSError:
        return None


def play_file_blocking(path, seconds):
    """Play a file of `seconds` at the PCM channel's volume and wait for it to end."""
    _channel("PCM")
    _link.call("sound", "play_file", {"wav_file": path, "volume": 100, "duration": seconds})
    if seconds > 0:
        time.sleep(seconds)


class Speaker:
    """The EV3's speaker: beeps, notes, sound files and speech (ev3dev_Speaker_*); there is one, so
    every Speaker() is the same object."""

    _the_speaker = None

    def __new__(cls, *args, **kwargs):
        if cls._the_speaker is None:
            speaker = super().__new__(cls)
            speaker._language, speaker._voice = "en", "m1"
            speaker._voice_setting = ""  # (set by set_speech_options only, as in the firmware)
            speaker._speed, speaker._pitch = "130", "50"
            set_channel_volume("PCM", 70)  # set_volume(100, '_default_'): "sset PCM 179, sset Beep 77"
            set_channel_volume("Beep", 30)
            cls._the_speaker = speaker
        return cls._the_speaker

    def __init__(self, *args, **kwargs):
        pass

    def beep(self, frequency=500, duration=100):
        """Beep at `frequency` Hz for `duration` ms and wait for it to end; a negative duration starts the
        beep and returns at once."""
        freq, ms = get_int(frequency), get_int(duration)
        if ms < 0:
            _channel("Beep")
            note = {"frequency": freq, "length_ms": 0, "delay_ms": 0, "repeats": 1}
            _link.call("sound", "beep", {"notes": [note], "duration": 0.0})
            return
        tone(freq, ms)

    def play_notes(self, notes, tempo=120):
        """Play notes such as 'C4/4' (name, octave 2-8, '/', fraction, then '.' for dotted and '_' for
        tied) at `tempo` quarter notes a minute; each untied note sounds 7/8 of its length."""
        whole_ms = _c_div(4 * 60 * 1000, get_int(tempo))
        for note in notes:
            self._play_note(note, whole_ms)

    @staticmethod
    def _play_note(note, whole_ms):
        if not isinstance(note, str):
            raise TypeError(f"can't convert '{type(note).__name__}' object to str implicitly")
        chars = note + "\0\0\0\0\0\0"  # (the firmware reads a C string: past its end is '\0')
        pos = 0
        name = chars[pos]
        pos += 1
        if name == "R":
            freq = 0.0
        elif name in _NOTES:
            sign = chars[pos] if chars[pos] in "#b" else ""
            pos += len(sign)
            freq = _NOTES[name][sign]
            if freq is None:
                raise ValueError(f"'{name}{sign}' is not allowed")
        else:
            raise ValueError("Missing note name A-G or R")
        if freq != 0:
            octave = ord(chars[pos]) - ord("0")
            pos += 1
            if octave < 2 or octave > 8:
                raise ValueError("Missing octave number 2-8")
            freq *= 2 << octave  # (the firmware's: A4 sounds at 880 Hz)
        if chars[pos] != "/":
            raise ValueError("Missing '/'")
        pos += 1
        fraction = ord(chars[pos]) - ord("0")
        pos += 1
        if fraction < 0 or fraction > 9:
            raise ValueError("Missing fractional value 1, 2, 4, 8, etc.")
        second = ord(chars[pos]) - ord("0")
        if 0 <= second <= 9:
            fraction = fraction * 10 + second
            pos += 1
        duration = _c_div(whole_ms, fraction)  # (a fraction of 0 divides by zero on the brick too)
        if chars[pos] == ".":
            duration = _c_div(3 * duration, 2)
            pos += 1
        release = chars[pos] != "_"
        _channel("Beep")
        if release:
            sound_ms, rest_ms = _c_div(7 * duration, 8), _c_div(duration, 8)
        else:
            sound_ms, rest_ms = duration, 0
        sound_ms, rest_ms = max(sound_ms, 0), max(rest_ms, 0)
        entry = {"frequency": int(freq), "length_ms": sound_ms, "delay_ms": rest_ms, "repeats": 1}
        entry["end_delay"] = True
        seconds = (sound_ms + rest_ms) / 1000
        _link.call("sound", "beep", {"notes": [entry], "duration": seconds})
        if seconds > 0:
            time.sleep(seconds)

    def play_file(self, file):
        """Play a sound file (a SoundFile, or a .wav file's path) and wait for it to end."""
        from .media.ev3dev import SoundFile

        if not isinstance(file, str):
            raise TypeError(f"can't convert '{type(file).__name__}' object to str implicitly")
        seconds = wav_seconds(file)
        if seconds is None:
            if file not in SoundFile._ALL:
                raise RuntimeError(f"Playing file failed: {file}: No such file or directory\n")
            seconds = SOUND_FILE_S
        play_file_blocking(file, seconds)

    def say(self, text):
        """Say `text` (with espeak on a brick) and wait until it is said."""
        if not isinstance(text, str):
            raise TypeError(f"can't convert '{type(text).__name__}' object to str implicitly")
        options = f"-a 200 -v {self._voice_setting} -s {self._speed} -p {self._pitch}"
        try:
            speed = int(self._speed)
        except ValueError:
            speed = ESPEAK_WPM
        seconds = len(text.split()) * 60.0 / max(speed, 80)  # (espeak's slowest speed is 80)
        _channel("PCM")
        _link.call(
            "sound", "speak", {"text": text, "espeak_opts": options, "volume": 100, "duration": seconds}
        )
        if seconds > 0:
            time.sleep(seconds)

    def set_speech_options(self, language=None, voice=None, speed=None, pitch=None):
        """Choose the language, voice, speed (words a minute) and pitch (0-99) of say()."""
        if language is not None:
            self._language = _c_string(language, 10)
        if voice is not None:
            self._voice = _c_string(voice, 10)
        self._voice_setting = f"{self._language}+{self._voice}"[:20]
        if speed is not None:
            self._speed = str(get_int(speed))[:7]
        if pitch is not None:
            self._pitch = str(get_int(pitch))[:7]

    def set_volume(self, volume, which="_all_"):
        """Set the volume, 0 to 100 %, of 'Beep' (beeps and notes), 'PCM' (files and speech) or both."""
        volume = max(0, min(100, get_int(volume)))
        if not isinstance(which, str):
            raise TypeError(f"can't convert '{type(which).__name__}' object to str implicitly")
        if which == "_default_":
            set_channel_volume("PCM", 70)
            set_channel_volume("Beep", 30)
        elif which == "_all_":
            set_channel_volume("PCM", volume)
            set_channel_volume("Beep", volume)
        elif which in ("Beep", "PCM"):
            set_channel_volume(which, volume)
        else:
            raise ValueError("which must be one of '_all_', 'Beep', 'PCM'")


def _c_string(value, size):
    """strncpy into a char[size] (the firmware's language and voice): at most size - 1 characters kept."""
    if not isinstance(value, str):
        raise TypeError(f"can't convert '{type(value).__name__}' object to str implicitly")
    return re.sub("\0.*", "", value)[: size - 1]
