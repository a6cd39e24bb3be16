"""
The brick's speaker (python-ev3dev2 2.1.0): beeps, tones, notes, songs, wav files and speech.

On a real EV3 these run the ``beep``, ``aplay``, ``espeak`` and ``amixer``
programs.  Here each sound is one ``_link.call('sound', kind, details)``:

- ``'beep'``: {'args': beep's argument string, 'notes': [{'frequency', 'length_ms',
  'delay_ms', 'repeats', 'end_delay'}], 'duration': seconds, 'play_type'}
- ``'play_file'``: {'wav_file', 'volume', 'duration', 'play_type'}
- ``'speak'``: {'text', 'espeak_opts', 'volume', 'duration', 'play_type'}
- ``'set_volume'``: {'pct', 'channel'}; ``'get_volume'``: {'channel'} -> int percent

and the program then sleeps for the sound's duration when it waits for it
to complete, as the real programs take that long.
"""

import os
import re
import shlex
import sys  # noqa: F401  (imported as upstream imports it, so a star import brings the same names)
import time
import wave
from subprocess import PIPE, Popen  # noqa: F401
from time import sleep  # noqa: F401  (only for star imports; the shim calls time.sleep, which a run replaces)

from ev3dev2 import _link, is_micropython  # noqa: F401

# Defaults of the `beep` program.
_BEEP_FREQUENCY = 440
_BEEP_LENGTH_MS = 200
_BEEP_DELAY_MS = 100

# espeak's default speed, in words per minute.
_ESPEAK_WPM = 175


def _make_scales(notes):
    """Builds the note frequencies table: one entry per note name, frequencies rounded."""
    res = dict()
    for note, freq in notes:
        freq = round(freq)
        for n in note.split("/"):
            res[n.upper()] = freq
    return res


def _beep_notes(args):
    """The notes a `beep` command line plays: -f Hz, -l ms, -r repeats, -D/-d delay ms, -n next note."""
    notes = []
    note = None
    tokens = shlex.split(args)
    i = 0
    while i <= len(tokens):
        token = tokens[i] if i < len(tokens) else "-n"
        if note is None:
            note = {
                "frequency": _BEEP_FREQUENCY,
                "length_ms": _BEEP_LENGTH_MS,
                "delay_ms": _BEEP_DELAY_MS,
                "repeats": 1,
                "end_delay": False,
            }
        if token in ("-n", "--new"):
            notes.append(note)
            note = None
        elif token in ("-f", "-l", "-r", "-D", "-d") and i + 1 < len(tokens):
            value = float(tokens[i + 1])
            i += 1
            if token == "-f":
                note["frequency"] = value
            elif token == "-l":
                note["length_ms"] = value
            elif token == "-r":
                note["repeats"] = int(value)
            else:
                note["delay_ms"] = value
                note["end_delay"] = token == "-d"
        i += 1
    return notes


def _beep_duration(notes):
    """Seconds `beep` takes: each repeat's length, plus the delay between repeats (and after, with -d)."""
    total_ms = 0.0
    for note in notes:
        repeats = max(note["repeats"], 0)
        delays = repeats if note["end_delay"] else max(repeats - 1, 0)
        total_ms += repeats * note["length_ms"] + delays * note["delay_ms"]
    return total_ms / 1000


def _wav_duration(wav_file):
    try:
        with wave.open(wav_file, "rb") as wav:
            return wav.getnframes() / float(wav.getframerate())
    except (OSError, EOFError, wave.Error):
        return 0.0


def _speech_duration(text, espeak_opts):
    match = re.search(r"-s\s*(\d+)", espeak_opts or "")
    words_per_minute = int(match.group(1)) if match else _ESPEAK_WPM
    return len(text.split()) * 60.0 / max(words_per_minute, 1)


class _SoundProcess:
    """Stands for the Popen object of a sound started without waiting: wait() or poll() it."""

    def __init__(self, duration):
        self.pid = None
        self._end = time.time() + duration
        self.returncode = None

    def poll(self):
        if self.returncode is None and time.time() >= self._end:
            self.returncode = 0
        return self.returncode

    def wait(self, timeout=None):
        remaining = self._end - time.time()
        if remaining > 0:
            time.sleep(remaining)
        self.returncode = 0
        return self.returncode


class Sound:
    """
    Beep, play tones, notes, songs and wav files, or speak text.

    Example::

        spkr = Sound()
        spkr.speak('Hello, I am Robot')
        spkr.play_song((('D4', 'e3'), ('D4', 'e3'), ('D4', 'e3'), ('G4', 'h'), ('D5', 'h')))

    Durations of the EV3-G style methods are in seconds.
    """

    channel = None

    # play_types
    PLAY_WAIT_FOR_COMPLETE = 0  #: Play the sound and block until it is complete
    PLAY_NO_WAIT_FOR_COMPLETE = 1  #: Start playing the sound but return immediately
    PLAY_LOOP = (
        2  #: Never return; start the sound immediately after it completes, until the program is killed
    )

    PLAY_TYPES = (PLAY_WAIT_FOR_COMPLETE, PLAY_NO_WAIT_FOR_COMPLETE, PLAY_LOOP)

    def _validate_play_type(self, play_type):
        assert play_type in self.PLAY_TYPES, "Invalid play_type {}, must be one of {}".format(
            play_type, ",".join(str(t) for t in self.PLAY_TYPES)
        )

    def _play(self, kind, details, duration, play_type):
        """Start the sound on the simulated brick and wait, return or loop as ``play_type`` says."""
        details = dict(details, duration=duration, play_type=play_type)

        if play_type == Sound.PLAY_WAIT_FOR_COMPLETE:
            _link.call("sound", kind, details)
            time.sleep(duration)
            return None

        elif play_type == Sound.PLAY_NO_WAIT_FOR_COMPLETE:
            _link.call("sound", kind, details)
            return _SoundProcess(duration)

        elif play_type == Sound.PLAY_LOOP:
            while True:
                _link.call("sound", kind, details)
                time.sleep(max(duration, 0.001))

        else:
            raise Exception(f"invalid play_type {play_type}")

    def beep(self, args="", play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        Beep, with the arguments of the Linux ``beep`` command (``-f`` Hz,
        ``-l`` ms, ``-r`` repeats, ``-D`` ms between repeats, ``-n`` next note).

        Returns, with PLAY_NO_WAIT_FOR_COMPLETE, an object standing for the
        beep process (wait() or poll() it); None otherwise.
        """
        notes = _beep_notes(args)
        return self._play("beep", {"args": args, "notes": notes}, _beep_duration(notes), play_type)

    def tone(self, *args, play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        ``tone(tone_sequence)``: play a list of (frequency Hz, duration ms, delay ms) tuples;
        ``tone(frequency, duration)``: play one tone of ``duration`` ms.

        See :py:meth:`play_song` for a musician-friendly notation.
        """

        def play_tone_sequence(tone_sequence):
            def beep_args(frequency=None, duration=None, delay=None):
                args = ""
                if frequency is not None:
                    args += f"-f {frequency} "
                if duration is not None:
                    args += f"-l {duration} "
                if delay is not None:
                    args += f"-D {delay} "

                return args

            return self.beep(" -n ".join([beep_args(*t) for t in tone_sequence]), play_type=play_type)

        if len(args) == 1:
            return play_tone_sequence(args[0])
        elif len(args) == 2:
            return play_tone_sequence([(args[0], args[1])])
        else:
            raise Exception(
                "Unsupported number of parameters in Sound.tone(): expected 1 or 2, got " + str(len(args))
            )

    def play_tone(self, frequency, duration, delay=0.0, volume=100, play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        Play one tone: ``frequency`` Hz for ``duration`` seconds, then ``delay``
        seconds, at ``volume`` percent.

        :raises ValueError: if a parameter is invalid
        """
        self._validate_play_type(play_type)

        if duration <= 0:
            raise ValueError(f"invalid duration ({duration})")
        if delay < 0:
            raise ValueError(f"invalid delay ({delay})")
        if not 0 < volume <= 100:
            raise ValueError(f"invalid volume ({volume})")

        self.set_volume(volume)

        duration_ms = int(duration * 1000)
        delay_ms = int(delay * 1000)

        self.tone([(frequency, duration_ms, delay_ms)], play_type=play_type)

    def play_note(self, note, duration, volume=100, play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        Play ``note`` (e.g. ``'C4'``, ``'D#5'``, ``'Gb3'``; see ``_NOTE_FREQUENCIES``)
        for ``duration`` seconds at ``volume`` percent.

        :raises ValueError: if a parameter is invalid
        """
        self._validate_play_type(play_type)
        try:
            freq = self._NOTE_FREQUENCIES.get(note.upper(), self._NOTE_FREQUENCIES[note])
        except KeyError:
            raise ValueError(f"invalid note ({note})")  # noqa: B904  (as upstream)

        if duration <= 0:
            raise ValueError(f"invalid duration ({duration})")
        if not 0 < volume <= 100:
            raise ValueError(f"invalid volume ({volume})")

        return self.play_tone(freq, duration=duration, volume=volume, play_type=play_type)

    def play_file(self, wav_file, volume=100, play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        Play the wav file ``wav_file`` at ``volume`` percent.

        Returns, with PLAY_NO_WAIT_FOR_COMPLETE, an object standing for the
        player process; None otherwise.
        """
        if not 0 < volume <= 100:
            raise ValueError(f"invalid volume ({volume})")

        if not wav_file.endswith(".wav"):
            raise ValueError(f"invalid sound file ({wav_file}), only .wav files are supported")

        if not os.path.exists(wav_file):
            raise ValueError(f"{wav_file} does not exist")

        self._validate_play_type(play_type)
        self.set_volume(volume)
        details = {"wav_file": wav_file, "volume": volume}
        return self._play("play_file", details, _wav_duration(wav_file), play_type)

    def speak(self, text, espeak_opts="-a 200 -s 130", volume=100, play_type=PLAY_WAIT_FOR_COMPLETE):
        """
        Speak ``text`` aloud (with ``espeak`` on a real EV3) at ``volume`` percent.

        Returns, with PLAY_NO_WAIT_FOR_COMPLETE, an object standing for the
        speech process; None otherwise.
        """
        self._validate_play_type(play_type)
        self.set_volume(volume)
        details = {"text": text, "espeak_opts": espeak_opts, "volume": volume}
        return self._play("speak", details, _speech_duration(text, espeak_opts), play_type)

    def _get_channel(self):
        """The mixer channel: 'Playback', the EV3's only one."""
        if self.channel is None:
            self.channel = "Playback"

        return self.channel

    def set_volume(self, pct, channel=None):
        """Set the sound volume to ``pct`` percent (an int, 0 to 100)."""
        if channel is None:
            channel = self._get_channel()

        f"{channel} {pct:d}%"  # amixer's argument: refuses a non-int pct as upstream does
        _link.call("sound", "set_volume", {"pct": pct, "channel": channel})

    def get_volume(self, channel=None):
        """The sound volume, in percent."""
        if channel is None:
            channel = self._get_channel()

        volume = _link.call("sound", "get_volume", {"channel": channel})
        if volume is None:
            raise Exception(f"Failed to parse output of ``amixer get {channel}``")
        return int(volume)

    def play_song(self, song, tempo=120, delay=0.05):
        """
        Play ``song``, a list of (note, value) tuples in musical notation:
        notes like ``A4``, ``D#3``, ``Gb5`` or ``R`` for a rest; values ``w``,
        ``h``, ``q``, ``e``, ``s`` (whole to sixteenth), with modifiers ``/3``
        (divider), ``*1.5`` (multiplier), ``3`` (triplet) or ``.`` (dotted).
        ``tempo`` is in quarters per minute (4/4 only); ``delay`` is seconds
        between notes.

        Example::

            Sound().play_song((('D4', 'e3'), ('D4', 'e3'), ('D4', 'e3'), ('G4', 'h'), ('D5', 'h')))

        :raises ValueError: if a note or parameter is invalid
        """
        if tempo <= 0:
            raise ValueError(f"invalid tempo ({tempo})")
        if delay < 0:
            raise ValueError(f"invalid delay ({delay})")

        delay_ms = int(delay * 1000)
        meas_duration_ms = 60000 / tempo * 4  # we only support 4/4 bars, hence "* 4"

        for note, value in song:
            value = value.lower()

            if "/" in value:
                base, factor = value.split("/")
                factor = float(factor)

            elif "*" in value:
                base, factor = value.split("*")
                factor = float(factor)

            elif value.endswith("."):
                base = value[:-1]
                factor = 1.5

            elif value.endswith("3"):
                base = value[:-1]
                factor = float(2 / 3)

            else:
                base = value
                factor = 1.0

            try:
                duration_ms = meas_duration_ms * self._NOTE_VALUES[base] * factor
            except KeyError:
                raise ValueError(f"invalid note ({base})")  # noqa: B904  (as upstream)

            if note == "R":
                time.sleep(duration_ms / 1000 + delay)
            else:
                freq = self._NOTE_FREQUENCIES[note.upper()]
                self.beep(f"-f {int(freq)} -l {int(duration_ms)} -D {int(delay_ms)}")

    #: Note frequencies, rounded, by US note name and octave (``C3``);
    #: ``#`` and ``b`` between note and octave for sharp and flat (``D#4``, ``Gb5``).
    _NOTE_FREQUENCIES = _make_scales(
        (
            ("C0", 16.35),
            ("C#0/Db0", 17.32),
            ("D0", 18.35),
            ("D#0/Eb0", 19.45),  # expanded in one entry per symbol by _make_scales
            ("E0", 20.60),
            ("F0", 21.83),
            ("F#0/Gb0", 23.12),
            ("G0", 24.50),
            ("G#0/Ab0", 25.96),
            ("A0", 27.50),
            ("A#0/Bb0", 29.14),
            ("B0", 30.87),
            ("C1", 32.70),
            ("C#1/Db1", 34.65),
            ("D1", 36.71),
            ("D#1/Eb1", 38.89),
            ("E1", 41.20),
            ("F1", 43.65),
            ("F#1/Gb1", 46.25),
            ("G1", 49.00),
            ("G#1/Ab1", 51.91),
            ("A1", 55.00),
            ("A#1/Bb1", 58.27),
            ("B1", 61.74),
            ("C2", 65.41),
            ("C#2/Db2", 69.30),
            ("D2", 73.42),
            ("D#2/Eb2", 77.78),
            ("E2", 82.41),
            ("F2", 87.31),
            ("F#2/Gb2", 92.50),
            ("G2", 98.00),
            ("G#2/Ab2", 103.83),
            ("A2", 110.00),
            ("A#2/Bb2", 116.54),
            ("B2", 123.47),
            ("C3", 130.81),
            ("C#3/Db3", 138.59),
            ("D3", 146.83),
            ("D#3/Eb3", 155.56),
            ("E3", 164.81),
            ("F3", 174.61),
            ("F#3/Gb3", 185.00),
            ("G3", 196.00),
            ("G#3/Ab3", 207.65),
            ("A3", 220.00),
            ("A#3/Bb3", 233.08),
            ("B3", 246.94),
            ("C4", 261.63),
            ("C#4/Db4", 277.18),
            ("D4", 293.66),
            ("D#4/Eb4", 311.13),
            ("E4", 329.63),
            ("F4", 349.23),
            ("F#4/Gb4", 369.99),
            ("G4", 392.00),
            ("G#4/Ab4", 415.30),
            ("A4", 440.00),
            ("A#4/Bb4", 466.16),
            ("B4", 493.88),
            ("C5", 523.25),
            ("C#5/Db5", 554.37),
            ("D5", 587.33),
            ("D#5/Eb5", 622.25),
            ("E5", 659.25),
            ("F5", 698.46),
            ("F#5/Gb5", 739.99),
            ("G5", 783.99),
            ("G#5/Ab5", 830.61),
            ("A5", 880.00),
            ("A#5/Bb5", 932.33),
            ("B5", 987.77),
            ("C6", 1046.50),
            ("C#6/Db6", 1108.73),
            ("D6", 1174.66),
            ("D#6/Eb6", 1244.51),
            ("E6", 1318.51),
            ("F6", 1396.91),
            ("F#6/Gb6", 1479.98),
            ("G6", 1567.98),
            ("G#6/Ab6", 1661.22),
            ("A6", 1760.00),
            ("A#6/Bb6", 1864.66),
            ("B6", 1975.53),
            ("C7", 2093.00),
            ("C#7/Db7", 2217.46),
            ("D7", 2349.32),
            ("D#7/Eb7", 2489.02),
            ("E7", 2637.02),
            ("F7", 2793.83),
            ("F#7/Gb7", 2959.96),
            ("G7", 3135.96),
            ("G#7/Ab7", 3322.44),
            ("A7", 3520.00),
            ("A#7/Bb7", 3729.31),
            ("B7", 3951.07),
            ("C8", 4186.01),
            ("C#8/Db8", 4434.92),
            ("D8", 4698.63),
            ("D#8/Eb8", 4978.03),
            ("E8", 5274.04),
            ("F8", 5587.65),
            ("F#8/Gb8", 5919.91),
            ("G8", 6271.93),
            ("G#8/Ab8", 6644.88),
            ("A8", 7040.00),
            ("A#8/Bb8", 7458.62),
            ("B8", 7902.13),
        )
    )

    #: Note values, as fractions of a whole note: w whole, h half, q quarter,
    #: e eighth, s sixteenth (see https://en.wikipedia.org/wiki/Note_value).
    _NOTE_VALUES = {
        "w": 1.0,
        "h": 1.0 / 2,
        "q": 1.0 / 4,
        "e": 1.0 / 8,
        "s": 1.0 / 16,
    }
