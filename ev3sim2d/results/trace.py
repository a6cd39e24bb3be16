"""What happened in a run: every tick's poses and motor states, sensor snapshots, printed lines.

The simulation appends to a Trace while it runs; renderers and graders read
it afterwards (or load it from a file written with `save`), never the live
simulation.  `fingerprint()` hashes everything that was recorded (rounded
to 1e-4 of its unit, so that last-bit floating point differences between
machines do not change it): two runs with the same fingerprint did the same.
"""

from __future__ import annotations

import hashlib
import json
from array import array
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .output_files import writing

FORMAT = "ev3sim2d-trace-1"

# columns of one robot in the motion table: its pose, whether its body touches a wall, and whether it
# touches another robot
POSE_COLUMNS = ("x_cm", "y_cm", "heading_deg", "touching", "touching_robot")
OLD_POSE_COLUMNS = 4  # traces saved before "touching_robot" was recorded: loaded with it 0 throughout
MOTOR_COLUMNS = ("position", "speed", "state")

# ------------------------------------------------------------------------------------------ budgets
# What one robot's brick may make the simulator keep, do and render in one run.  A brick is a student's
# program: the protocol bounds one message (8 MiB), these bound what its messages add up to.  The
# simulator's end of the brick (simulator/brick_port.py) ends that brick's run at the first budget it
# exceeds, with a reason that names it, and the run goes on for the other robots; the renderer
# (render/timeline.py, audio.py) plays a trace made without them (an older run's, one made by hand)
# within the sound budgets.  The motion table and the sensor samples need no budget: they grow with
# virtual time only (one row per tick; at most SAMPLES_PER_TICK samples of a sensor per tick,
# devices/sensor.py), which the run's time limit bounds.  docs/grading-security.md (Budgets) has the table.

PRINTED_LINES = 20_000
"""Lines a program may print in a run.  A program that logs its sensors every 10 ms for 60 s prints
6,000; printing costs a brick 1 ms a line, so no honest 60 s run prints more than 60,000."""

PRINTED_BYTES = 2_000_000
"""Bytes a program may print in a run (UTF-8, counted as sent, before long lines are cut): the 10 ms
logger's 6,000 lines of some 60 characters are 360 kB."""

PRINTED_LINE_CHARS = 2_000
"""Characters of one printed line that are kept; the rest is cut (and the cut said).  Not a budget."""

EVENTS = 20_000
"""Sounds, LED changes and LCD frames a brick may record in a run, together.  A program that turns
both LEDs red and green every 100 ms records 2,400 a minute, one that beeps every 100 ms 600, one that
draws a changing screen all the time 1,200 (see LCD_FRAMES)."""

LCD_FRAMES = 3_000
"""Different LCD pictures a brick may leave in a run (178 x 128 bytes each: 68 MB at most).  A picture is
kept as the EV3's screen shows it: at most one per LCD_REFRESH_US (a draw within the refresh of the last
picture kept replaces it), and a picture like the last one is not kept again; a program that draws a
screen that changes every tick for 60 s keeps 1,200."""

LCD_REFRESH_US = 50_000
"""How often the EV3's screen shows a new picture at most: the st7586 LCD driver's update delay, HZ / 20."""

LCD_DRAWS_PER_REFRESH = 4
"""Draws of the LCD within one refresh that are events of their own (each counting in EVENTS); a later
one within it moves the last to its time and picture.  A loop that draws after each 2 ms read draws 25
times a refresh, which the screen could not show either.  Not a budget."""

SOUND_NOTES = 10_000
"""Notes a brick's beeps may hold in a run, a note's repeats each counting as one (a video synthesises
each): a song of 100 notes is 100, a beep every 10 ms for 60 s is 6,000.  One beep holds at most
NOTES_PER_SOUND notes."""

NOTES_PER_SOUND = 100
"""Notes one beep may hold (the notes beyond are not kept).  Not a budget: a cut, as for a line."""

SOUND_NUMBERS = {
    "frequency": (0.0, 20_000.0),
    "length_ms": (0.0, 60_000.0),
    "delay_ms": (0.0, 60_000.0),
    "repeats": (0, 100),
    "duration": (0.0, 3_600.0),
    "volume": (0.0, 100.0),
    "pct": (0.0, 100.0),
    "play_type": (0, 10),
}
"""The range of each number a sound event holds (a note's: frequency to repeats): the brick port keeps
a sound's numbers within them, and the renderer a hand-made trace's.  Not a budget."""

SOUND_SECONDS = 600.0
"""Seconds of sound a brick may play in a run, all added up: its beeps' tones (which a video synthesises)
and its speech and sound files (which a video captions while they play).  A 60 s run that beeps all the
time plays 60, a song in a sound file some 200; ten times the first leaves room for sounds started
without waiting for the last."""

KEYS = 10_000
"""Device attributes a brick may name in a run (its keys; each names a different one): a robot has
about 200 (4 motors and 4 sensors of some 20 attributes, the LEDs, the battery)."""

NAME_CHARS = 255
"""Characters of a class, device or attribute name: a longer one cannot be a sysfs file (NAME_MAX), and
is answered ENAMETOOLONG without being kept.  Not a budget."""

OPS_BURST = 20_000
"""Operations a brick may send at any moment of its clock; OPS_PER_SECOND more for each second of it."""

OPS_PER_SECOND = 20_000
"""Operations a brick may send for each second of its virtual clock, beyond OPS_BURST.  Each operation
an honest program sends costs it virtual time (2 ms a read, 3 ms a write, 1 ms a printed line) but its
calls to the speaker and the LCD: the busiest honest loop sends about 1,000 a second.  Without it a
brick whose clock stands still, or creeps on by a microsecond, could keep the simulator busy for ever."""


@dataclass
class OutputLine:
    """A line a program printed."""

    t_s: float
    robot: int
    stream: str  # 'stdout' or 'stderr'
    text: str


@dataclass
class Trace:
    """The record of one run."""

    tick_s: float
    robots: list[dict]  # per robot: name, spec (dict), start pose, motor ports, sensor ports + kinds
    world: dict  # name, title, YAML text of the world file
    seed: int
    times: array = field(default_factory=lambda: array("d"))
    values: array = field(
        default_factory=lambda: array("d")
    )  # per tick, per robot: pose + motor columns, flat
    # every sensor measurement, when the program read it or a periodic snapshot took it:
    # [t_s, robot index, port, mode, [values as the driver gives them]]
    sensor_samples: list[list] = field(default_factory=list)
    output: list[OutputLine] = field(default_factory=list)
    # what the brick did besides moving: [t_s, robot index, kind, data]; kinds: 'sound' (data: the
    # sound's kind and details, see ev3dev2/sound.py), 'leds' (brightness 0..255 by LED name),
    # 'lcd' (data: {'frame': index into lcd_frames})
    events: list[list] = field(default_factory=list)
    lcd_frames: list[bytes] = field(default_factory=list)  # 178 x 128 bytes of 8-bit grey, row by row
    result: dict = field(default_factory=dict)  # status, error, ... filled in at the end
    # per robot, the motors as the run ended: {"driving": wheels still driven, "states": {port: state}}
    end_motors: list[dict] = field(default_factory=list)

    # ------------------------------------------------------------ recording
    @property
    def width(self) -> int:
        """Columns per tick: for each robot its pose columns, then its motor columns."""
        return sum(len(POSE_COLUMNS) + len(MOTOR_COLUMNS) * len(r["motors"]) for r in self.robots)

    def add_tick(self, t_s: float, row: list) -> None:
        self.times.append(t_s)
        self.values.fromlist(row)  # (half what extend costs, for a list)

    def add_output(self, line: OutputLine) -> None:
        self.output.append(line)

    def add_event(self, t_s: float, robot: int, kind: str, data: dict) -> None:
        self.events.append([t_s, robot, kind, data])

    def add_lcd_frame(self, pixels: bytes) -> int:
        self.lcd_frames.append(pixels)
        return len(self.lcd_frames) - 1

    # -------------------------------------------------------------- reading
    def motion(self) -> np.ndarray:
        """ticks × columns: for each robot, x, y, heading, touching (a wall), touching_robot, then
        position/speed/state per motor."""
        return np.frombuffer(self.values, dtype=float).reshape(len(self.times), self.width).copy()

    def robot_columns(self, index: int) -> slice:
        start = 0
        for i, r in enumerate(self.robots):
            width = len(POSE_COLUMNS) + len(MOTOR_COLUMNS) * len(r["motors"])
            if i == index:
                return slice(start, start + width)
            start += width
        raise IndexError(index)

    def poses(self, index: int) -> np.ndarray:
        """ticks × (x_cm, y_cm, heading_deg) of one robot, starting with its start pose."""
        start = self.robots[index]["start"]
        first = np.array([[start["x_cm"], start["y_cm"], start["heading_deg"]]])
        m = self.motion()
        if not len(m):
            return first
        cols = self.robot_columns(index)
        return np.vstack([first, m[:, cols][:, :3]])

    def fingerprint(self) -> str:
        h = hashlib.sha256()
        h.update(np.round(np.asarray(self.times) * 1e6).astype(np.int64).tobytes())
        h.update(np.round(self.motion() * 1e4).astype(np.int64).tobytes())
        h.update(json.dumps(self.sensor_samples, separators=(",", ":")).encode())
        h.update(json.dumps([[round(o.t_s, 6), o.robot, o.stream, o.text] for o in self.output]).encode())
        h.update(json.dumps(self.events, separators=(",", ":"), default=str).encode())
        for frame in self.lcd_frames:
            h.update(frame)
        h.update(json.dumps({k: self.result.get(k) for k in ("status", "error_type")}).encode())
        return h.hexdigest()[:16]

    # ---------------------------------------------------------------- files
    def save(self, path: str | Path) -> None:
        meta = {
            "format": FORMAT,
            "tick_s": self.tick_s,
            "robots": self.robots,
            "world": self.world,
            "seed": self.seed,
            "sensor_samples": self.sensor_samples,
            "output": [o.__dict__ for o in self.output],
            "events": self.events,
            "result": self.result,
            "end_motors": self.end_motors,
        }
        with writing(path) as temporary, open(temporary, "wb") as f:
            np.savez_compressed(
                f,
                times=np.asarray(self.times, dtype=float),
                motion=self.motion(),
                lcd=np.frombuffer(b"".join(self.lcd_frames), dtype=np.uint8).reshape(-1, 128, 178),
                meta=np.frombuffer(json.dumps(meta).encode(), dtype=np.uint8),
            )

    def _current_columns(self, motion: np.ndarray) -> np.ndarray:
        """A saved motion table in today's columns: one saved before robot contacts were recorded gets
        a `touching_robot` column of zeros (nothing said it touched a robot) after each robot's `touching`."""
        if motion.ndim != 2 or motion.shape[1] == self.width:
            return motion
        old_widths = [OLD_POSE_COLUMNS + len(MOTOR_COLUMNS) * len(r["motors"]) for r in self.robots]
        if motion.shape[1] != sum(old_widths):
            raise ValueError(f"a trace of {motion.shape[1]} columns for robots needing {self.width}")
        parts, start = [], 0
        for width in old_widths:
            block = motion[:, start : start + width]
            zeros = np.zeros((len(motion), len(POSE_COLUMNS) - OLD_POSE_COLUMNS))
            parts += [block[:, :OLD_POSE_COLUMNS], zeros, block[:, OLD_POSE_COLUMNS:]]
            start += width
        return np.hstack(parts)

    @classmethod
    def load(cls, path: str | Path) -> Trace:
        with np.load(path) as data:
            meta = json.loads(bytes(data["meta"]).decode())
            if meta.get("format") != FORMAT:
                raise ValueError(f"{path}: not an ev3sim2d trace (format {meta.get('format')!r})")
            trace = cls(meta["tick_s"], meta["robots"], meta["world"], meta["seed"])
            trace.times = array("d", data["times"].tolist())
            trace.values = array("d", trace._current_columns(data["motion"]).ravel().tolist())
            trace.lcd_frames = [frame.tobytes() for frame in data["lcd"]]
        trace.sensor_samples = meta["sensor_samples"]
        trace.output = [OutputLine(**o) for o in meta["output"]]
        trace.events = meta["events"]
        trace.result = meta["result"]
        trace.end_motors = meta.get("end_motors", [])
        return trace
