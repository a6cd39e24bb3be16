"""Looking the trace up by time: a frame at t shows the last tick at or before t; sounds as they play."""

import pytest

from ev3sim2d.render.timeline import Timeline, sound_spans
from ev3sim2d.results.trace import Trace

ROBOT = {
    "name": "robot",
    "start": {"x_cm": 10.0, "y_cm": 20.0, "heading_deg": 0.0},
    "motors": [["outB", "large"]],
    "sensors": [],
}


def tiny_trace():
    trace = Trace(0.01, [ROBOT], {"name": "t", "title": "t", "text": ""}, 0)
    for k in range(1, 4):  # ticks ending at 0.01, 0.02, 0.03 s
        trace.add_tick(k / 100, [10.0 + k, 20.0, 0.0, 0.0, 0.0, 36.0 * k, 360.0, 1])  # pose, contacts, motor
    return trace


def test_a_frame_shows_the_last_tick_at_or_before_its_time():
    timeline = Timeline(tiny_trace())
    assert timeline.tick_at(0.0) == -1 and timeline.pose(0, -1) == (10.0, 20.0, 0.0)
    assert timeline.tick_at(0.0199) == 0
    assert timeline.tick_at(0.1 + 0.2 - 0.28) == 1  # 0.020000000000000018: float sums still find tick 2
    assert timeline.pose(0, timeline.tick_at(1.0)) == (13.0, 20.0, 0.0)
    assert timeline.motors(0, 2) == [(108.0, 360.0, 1)]


def test_beep_notes_play_one_after_another_with_their_delays():
    trace = tiny_trace()
    notes = [
        {"frequency": 440, "length_ms": 100, "delay_ms": 50, "repeats": 2, "end_delay": False},
        {"frequency": 880, "length_ms": 200, "delay_ms": 0, "repeats": 1, "end_delay": False},
    ]
    trace.add_event(1.0, 0, "sound", {"kind": "set_volume", "pct": 50})
    trace.add_event(2.0, 0, "sound", {"kind": "beep", "notes": notes, "duration": 0.45})
    trace.add_event(3.0, 0, "sound", {"kind": "speak", "text": "hi", "duration": 0.5, "volume": 100})
    spans = sound_spans(trace)
    assert [(s.kind, s.start_s, s.end_s, s.frequency) for s in spans] == [
        ("tone", 2.0, pytest.approx(2.1), 440.0),
        ("tone", pytest.approx(2.15), pytest.approx(2.25), 440.0),
        ("tone", pytest.approx(2.25), pytest.approx(2.45), 880.0),
        ("speech", 3.0, 3.5, 0.0),
    ]
    assert spans[0].volume == 0.5 and spans[-1].text == "hi"
    timeline = Timeline(trace)
    assert [s.frequency for s in timeline.sounds_at(0, 2.3)] == [880.0]
    assert timeline.sounds_at(0, 2.12) == []


def test_leds_and_screen_as_last_set():
    trace = tiny_trace()
    trace.add_event(0.5, 0, "leds", {"led0:red:brick-status": 255})
    trace.add_event(0.7, 0, "lcd", {"frame": trace.add_lcd_frame(bytes(178 * 128))})
    timeline = Timeline(trace)
    assert timeline.leds(0, 0.4) == {} and timeline.leds(0, 0.5) == {"led0:red:brick-status": 255}
    assert timeline.lcd_frame(0, 0.6) is None and timeline.lcd_frame(0, 0.8) == 0
