"""The run's sound track: the beeps, tones and notes of the trace, synthesised at video speed.

A tone keeps its pitch when the video plays faster than the run (`speed` 2:
each note lasts half as long, at the same frequency).  Spoken text and sound
files are shown as captions instead (the trace keeps the words and the file
name, not the audio).  Only what the video's length holds is synthesised, and
the tones are a run's budget's worth at most (timeline.sound_spans), so a
trace's sounds cannot make a video take long.
"""

from __future__ import annotations

import numpy as np

from .timeline import SoundSpan

SAMPLE_RATE = 44100
LEVEL = 0.25  # peak of a tone at 100 % volume: room to add overlapping robots
EDGE_S = 0.004  # fade in and out, so that tones do not click


def tone_samples(
    frequency: float, seconds: float, volume: float, rate: int = SAMPLE_RATE, keep: int | None = None
) -> np.ndarray:
    """A tone like the EV3 speaker's: a fundamental with a little third harmonic, faded at both ends; only
    its first `keep` samples (all: None), as those of the whole tone."""
    n = max(int(round(seconds * rate)), 0)
    m = n if keep is None else max(min(n, keep), 0)
    t = np.arange(m) / rate
    wave = np.sin(2 * np.pi * frequency * t)
    if 3 * frequency < rate / 2:
        wave += 0.25 * np.sin(2 * np.pi * 3 * frequency * t)
    wave *= LEVEL * volume / 1.25
    edge = min(int(EDGE_S * rate), n // 2)
    if edge > 0:
        ramp = np.linspace(0.0, 1.0, edge)
        wave[: min(edge, m)] *= ramp[:m]
        if m > n - edge:
            wave[n - edge : m] *= ramp[::-1][: m - (n - edge)]
    return wave.astype(np.float32)


def sound_track(
    sounds: list[SoundSpan], length_s: float, speed: float = 1.0, rate: int = SAMPLE_RATE
) -> np.ndarray | None:
    """Mono float samples for a video `length_s` long showing the run at `speed`; None when nothing sounds."""
    tones = [s for s in sounds if s.kind == "tone" and s.end_s > s.start_s and s.volume > 0]
    if not tones:
        return None
    track = np.zeros(int(np.ceil(length_s * rate)) + 1, dtype=np.float32)
    for s in tones:
        start = int(round(s.start_s / speed * rate))
        if start >= len(track):
            continue
        samples = tone_samples(s.frequency, (s.end_s - s.start_s) / speed, s.volume, rate, len(track) - start)
        track[start : start + len(samples)] += samples
    np.clip(track, -1.0, 1.0, out=track)
    return track
