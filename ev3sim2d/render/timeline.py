"""The trace indexed by time, for drawing: what every robot, sensor, LED, screen and speaker did at time t.

A frame at time t shows the last tick that ended at or before t (the start
pose before the first tick), each sensor's last measurement, the LEDs and the
screen as last set, and the sounds playing at t.
"""

from __future__ import annotations

import os
from bisect import bisect_right
from dataclasses import dataclass

import numpy as np

from ..results.trace import (
    EVENTS,
    MOTOR_COLUMNS,
    NOTES_PER_SOUND,
    POSE_COLUMNS,
    SOUND_NOTES,
    SOUND_NUMBERS,
    SOUND_SECONDS,
    OutputLine,
    Trace,
)

_EPS_S = 1e-9  # frame times are sums of floats: t = 0.1 must find the tick that ended at 0.1
_SOUND_BUCKET_S = 1.0  # sounds_at looks among the sounds playing in the second of t only


@dataclass(frozen=True)
class SoundSpan:
    """One sound as it plays: a tone of `frequency` Hz, spoken `text`, or a sound file named in `text`."""

    robot: int
    start_s: float
    end_s: float
    kind: str  # 'tone', 'speech' or 'file'
    frequency: float = 0.0
    text: str = ""
    volume: float = 1.0  # 0..1


class Timeline:
    """Look-ups into one trace by simulated time."""

    def __init__(self, trace: Trace) -> None:
        self.trace = trace
        self.times = np.asarray(trace.times, dtype=float)
        self.motion = trace.motion()
        last_tick = float(self.times[-1]) if len(self.times) else 0.0
        self.end_s = max(last_tick, float(trace.result.get("sim_time_s") or 0.0))
        self.robot_count = len(trace.robots)
        self._columns = [trace.robot_columns(i) for i in range(self.robot_count)]
        self.starts = [
            (r["start"]["x_cm"], r["start"]["y_cm"], r["start"]["heading_deg"]) for r in trace.robots
        ]

        self._sensor_times: dict[tuple[int, str], list[float]] = {}
        self._sensor_values: dict[tuple[int, str], list[tuple[str, list[int]]]] = {}
        for t, robot, port, mode, values in trace.sensor_samples:
            self._sensor_times.setdefault((robot, port), []).append(t)
            self._sensor_values.setdefault((robot, port), []).append((mode, values))

        self._led_times: list[list[float]] = [[] for _ in trace.robots]
        self._led_states: list[list[dict]] = [[] for _ in trace.robots]
        self._lcd_times: list[list[float]] = [[] for _ in trace.robots]
        self._lcd_frames: list[list[int]] = [[] for _ in trace.robots]
        for event in trace.events:
            t, robot, kind, data = event if len(event) == 4 else (0.0, -1, "", None)
            if type(robot) is not int or not 0 <= robot < self.robot_count:
                continue  # (a hand-made trace's nonsense, or a change to the world: robot -1)
            if kind == "leds":
                self._led_times[robot].append(t)
                self._led_states[robot].append(data)
            elif kind == "lcd":
                self._lcd_times[robot].append(t)
                self._lcd_frames[robot].append(data["frame"])
        self.sounds = sound_spans(trace)
        self._sound_buckets: dict[tuple[int, int], list[SoundSpan]] = {}  # (robot, second) -> its sounds
        for span in self.sounds:  # (a budget's worth of sounds: at most SOUND_SECONDS long, all added up)
            first = int(span.start_s // _SOUND_BUCKET_S)
            for second in range(first, max(int(span.end_s // _SOUND_BUCKET_S), first) + 1):
                self._sound_buckets.setdefault((span.robot, second), []).append(span)
        self._output_times = [line.t_s for line in trace.output]

        touching = POSE_COLUMNS.index("touching")
        self._contact_ticks = []
        for cols in self._columns:
            flags = self.motion[:, cols][:, touching] if len(self.motion) else np.zeros(0)
            rises = np.flatnonzero(np.diff(np.concatenate([[0.0], flags])) > 0)
            self._contact_ticks.append(rises)

    # -------------------------------------------------------------- motion
    def tick_at(self, t_s: float) -> int:
        """Index of the last tick that ended at or before t_s; -1 before the first."""
        return bisect_right(self.times, t_s + _EPS_S) - 1

    def pose(self, robot: int, tick: int) -> tuple[float, float, float]:
        """x_cm, y_cm, heading_deg after `tick` (the start pose for -1)."""
        if tick < 0:
            return self.starts[robot]
        row = self.motion[tick, self._columns[robot]]
        return (float(row[0]), float(row[1]), float(row[2]))

    def path(self, robot: int, first: int, last: int) -> np.ndarray:
        """x, y (cm) after ticks first..last (inclusive; -1 is the start), as an n × 2 array."""
        first, last = max(first, -1), min(last, len(self.times) - 1)
        if last < first:
            return np.zeros((0, 2))
        cols = self._columns[robot]
        points = self.motion[max(first, 0) : last + 1, cols.start : cols.start + 2]
        if first < 0:
            points = np.vstack([self.starts[robot][:2], points])
        return points

    def touching(self, robot: int, tick: int) -> bool:
        if tick < 0:
            return False
        return bool(self.motion[tick, self._columns[robot].start + POSE_COLUMNS.index("touching")])

    def contact_ticks(self, robot: int) -> np.ndarray:
        """The ticks at which the robot began to touch something."""
        return self._contact_ticks[robot]

    def motors(self, robot: int, tick: int) -> list[tuple[float, float, int]]:
        """(position °, speed °/s, state bits) of each motor, in the trace's motor order."""
        count = len(self.trace.robots[robot]["motors"])
        if tick < 0:
            return [(0.0, 0.0, 0)] * count
        start = self._columns[robot].start + len(POSE_COLUMNS)
        row = self.motion[tick, start : start + len(MOTOR_COLUMNS) * count]
        return [(float(row[3 * i]), float(row[3 * i + 1]), int(row[3 * i + 2])) for i in range(count)]

    # ------------------------------------------------------------ the brick
    def sensor(self, robot: int, port: str, t_s: float) -> tuple[str, list[int]] | None:
        """The sensor's last measurement (mode, values as the driver gives them) at or before t_s."""
        times = self._sensor_times.get((robot, port))
        if not times:
            return None
        i = bisect_right(times, t_s + _EPS_S) - 1
        return self._sensor_values[(robot, port)][i] if i >= 0 else None

    def leds(self, robot: int, t_s: float) -> dict[str, int]:
        """Brightness (0..255) by LED name, as last set at or before t_s (all off before)."""
        i = bisect_right(self._led_times[robot], t_s + _EPS_S) - 1
        return self._led_states[robot][i] if i >= 0 else {}

    def lcd_frame(self, robot: int, t_s: float) -> int | None:
        """Index into trace.lcd_frames of what the screen showed at t_s; None before the program drew."""
        i = bisect_right(self._lcd_times[robot], t_s + _EPS_S) - 1
        return self._lcd_frames[robot][i] if i >= 0 else None

    def used_lcd(self, robot: int) -> bool:
        return bool(self._lcd_times[robot])

    def made_sounds(self, robot: int) -> bool:
        return any(s.robot == robot for s in self.sounds)

    def sounds_at(self, robot: int, t_s: float) -> list[SoundSpan]:
        """The robot's sounds playing at t_s."""
        near = self._sound_buckets.get((robot, int((t_s + _EPS_S) // _SOUND_BUCKET_S)), ())
        return [s for s in near if s.start_s <= t_s + _EPS_S < s.end_s]

    def printed(self, t_s: float) -> list[OutputLine]:
        """The lines printed at or before t_s."""
        return self.trace.output[: bisect_right(self._output_times, t_s + _EPS_S)]


def _number(value, key: str, default: float) -> float:
    """A sound's number as the trace holds it, within its range (SOUND_NUMBERS); the default for anything
    else (a hand-made trace may hold text, NaN or 10**9 repeats)."""
    low, high = SOUND_NUMBERS[key]
    if type(value) not in (int, float) or value != value:
        return default
    return float(min(max(value, low), high))


def sound_spans(trace: Trace) -> list[SoundSpan]:
    """Every tone, speech and sound file of the run, in the order they start.

    A `beep` plays its notes one after another, each `repeats` times, with
    `delay_ms` between repeats (and after the last with `end_delay`), as the
    `beep` program does; volume is the robot's last `set_volume` (100 % at first).
    A run's sounds are played within its budgets (results/trace.py), whatever the trace holds (one made
    before the budgets, or by hand): each robot's first SOUND_NOTES tones, EVENTS speeches and sound
    files, and SOUND_SECONDS of sound in all; the rest is left out.
    """
    spans: list[SoundSpan] = []
    count = len(trace.robots)
    volume = [1.0] * count
    tones, others, seconds = [0] * count, [0] * count, [0.0] * count
    for event in trace.events:
        if type(event) is not list or len(event) != 4:
            continue
        t, robot, kind, data = event
        if kind != "sound" or type(robot) is not int or not 0 <= robot < count or type(data) is not dict:
            continue
        if type(t) not in (int, float) or not 0 <= t <= 1e9:  # (a time a float holds, not NaN)
            continue
        t = float(t)
        sound = data.get("kind")
        if sound == "set_volume":
            volume[robot] = _number(data.get("pct", 100), "pct", 100.0) / 100
        elif sound == "beep" and tones[robot] < SOUND_NOTES and seconds[robot] < SOUND_SECONDS:
            at = t
            notes = data.get("notes")
            for note in notes[:NOTES_PER_SOUND] if type(notes) is list else ():
                if type(note) is not dict:
                    continue
                repeats = int(_number(note.get("repeats", 1), "repeats", 1))
                length = _number(note.get("length_ms", 200), "length_ms", 200.0) / 1000
                delay = _number(note.get("delay_ms", 100), "delay_ms", 100.0) / 1000
                frequency = _number(note.get("frequency", 440), "frequency", 440.0)
                for r in range(repeats):
                    if tones[robot] >= SOUND_NOTES or seconds[robot] + length > SOUND_SECONDS:
                        break
                    tones[robot] += 1
                    seconds[robot] += length
                    spans.append(SoundSpan(robot, at, at + length, "tone", frequency, "", volume[robot]))
                    at += length
                    if r < repeats - 1 or note.get("end_delay"):
                        at += delay
        elif sound in ("speak", "play_file") and others[robot] < EVENTS:
            duration = _number(data.get("duration") or 0.0, "duration", 0.0)
            if seconds[robot] + duration > SOUND_SECONDS:
                continue
            others[robot] += 1
            seconds[robot] += duration
            text = (
                str(data.get("text", ""))[:500]
                if sound == "speak"
                else os.path.basename(str(data.get("wav_file", ""))[:500])
            )
            level = _number(data.get("volume", 100), "volume", 100.0) / 100 * volume[robot]
            spans.append(
                SoundSpan(robot, t, t + duration, "speech" if sound == "speak" else "file", 0.0, text, level)
            )
    spans.sort(key=lambda s: (s.start_s, s.robot))
    return spans
