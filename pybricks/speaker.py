"""EV3 MicroPython 1.0's speaker: Speaker('EV3') (pybricks.speaker, kept in Pybricks 2.0 for 1.0 programs).

pybricks-micropython v2.0.0, bricks/ev3dev/modules/pybricks/speaker.py: beep(frequency=500, duration=100,
volume=30), beeps(number), tune(frequencies_and_durations, volume=30), file(file_name, volume=30) and
speech(text, volume=30), which on the brick says nothing.  Each sets the Beep or PCM volume first, and
blocks until its sound has ended (uev3dev/sound.py Sound._beep, Sound.play_file with PlayType.WAIT).
"""

from . import _speaker
from .tools import wait


class SoundFileError(Exception):
    """A sound file that cannot be read (uev3dev/sound.py SoundFile, from libsndfile's sf_open)."""


class Speaker:
    """Play beeps and sound files using a speaker."""

    _valid_devices = ["EV3"]

    def __init__(self, device_type):
        assert device_type in self._valid_devices, "Selected device is not supported."
        self._loaded_files = {}

    def beep(self, frequency=500, duration=100, volume=30):
        """Beep at `frequency` Hz for `duration` ms at `volume` percent."""
        _speaker.set_channel_volume("Beep", int(volume))
        _speaker.tone(int(frequency), int(duration))

    def beeps(self, number):
        """Beep `number` times, 100 ms apart."""
        for _ in range(number):
            self.beep()
            wait(100)

    def tune(self, frequencies_and_durations, volume=30):
        """Play (frequency Hz, duration ms) pairs one after another."""
        for frequency, duration in frequencies_and_durations:
            self.beep(frequency, duration, volume)

    def file(self, file_name, volume=30):
        """Play a sound file at `volume` percent and wait for it to end."""
        from .media.ev3dev import SoundFile

        if file_name not in self._loaded_files:
            seconds = _speaker.wav_seconds(file_name) if file_name.lower().endswith(".wav") else None
            if seconds is None and file_name in SoundFile._ALL:
                seconds = _speaker.SOUND_FILE_S
            if seconds is None:
                raise SoundFileError("System error : No such file or directory.")
            self._loaded_files[file_name] = seconds
        _speaker.set_channel_volume("PCM", int(volume))
        _speaker.play_file_blocking(file_name, self._loaded_files[file_name])

    def speech(self, text, volume=30):
        """Says nothing: the 1.0 compatibility module of Pybricks 2.0 leaves it to do (a TODO there)."""
        pass
