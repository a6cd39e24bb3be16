"""The sound track: tones where the trace has them, at their pitch whatever the video's speed."""

import numpy as np

from ev3sim2d.render.audio import SAMPLE_RATE, sound_track
from ev3sim2d.render.timeline import SoundSpan


def peak_hz(samples):
    spectrum = np.abs(np.fft.rfft(samples))
    return np.fft.rfftfreq(len(samples), 1 / SAMPLE_RATE)[int(np.argmax(spectrum))]


def test_a_tone_sounds_at_its_time_and_pitch():
    track = sound_track([SoundSpan(0, 1.0, 1.5, "tone", 440.0)], length_s=2.0)
    assert np.abs(track[:SAMPLE_RATE]).max() == 0
    assert abs(peak_hz(track[int(1.1 * SAMPLE_RATE) : int(1.4 * SAMPLE_RATE)]) - 440) < 5
    assert np.abs(track[int(1.51 * SAMPLE_RATE) :]).max() == 0


def test_at_double_speed_a_tone_comes_twice_as_early_and_lasts_half_as_long_at_the_same_pitch():
    track = sound_track([SoundSpan(0, 1.0, 1.5, "tone", 880.0)], length_s=1.0, speed=2.0)
    loud = np.flatnonzero(np.abs(track) > 0.01)
    assert abs(loud[0] / SAMPLE_RATE - 0.5) < 0.01 and abs(loud[-1] / SAMPLE_RATE - 0.75) < 0.01
    assert abs(peak_hz(track[int(0.52 * SAMPLE_RATE) : int(0.73 * SAMPLE_RATE)]) - 880) < 10


def test_no_tones_no_track():
    assert sound_track([SoundSpan(0, 0.0, 1.0, "speech", text="hello")], length_s=1.0) is None
