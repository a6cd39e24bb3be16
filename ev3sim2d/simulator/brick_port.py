"""The simulator's end of one brick's connection: its ops applied to its robot's devices, in order.

A brick sends what its program did (see ev3sim2d/protocol/messages.py); the
port queues the ops and applies them when the session lets it: writes go to
the robot's devices, calls to the speaker, LCD and buttons, printed lines and
events to the trace.  Everything a brick sends is checked: it is a student's
program at the other end, and anything that is not the protocol (a wrong key,
time running backwards, a message too large) ends that brick's run.  What a
brick makes the simulator keep and do is bounded by its run's budgets
(results/trace.py): printed lines and bytes, sounds, LED changes and LCD frames,
notes and seconds of sound, keys, operations for the time its clock passed;
past one, its run ends (OverBudget), with a reason that names the budget.
"""

from __future__ import annotations

import errno
import math
import os
from collections import deque

from ..devices.brick import Brick
from ..protocol import ProtocolError
from ..results.trace import (
    EVENTS,
    KEYS,
    LCD_DRAWS_PER_REFRESH,
    LCD_FRAMES,
    LCD_REFRESH_US,
    NAME_CHARS,
    NOTES_PER_SOUND,
    OPS_BURST,
    OPS_PER_SECOND,
    PRINTED_BYTES,
    PRINTED_LINE_CHARS,
    PRINTED_LINES,
    SOUND_NOTES,
    SOUND_NUMBERS,
    SOUND_SECONDS,
    OutputLine,
)

LCD_BYTES = 178 * 128
PENDING_REQUESTS = 100  # requests (R, W, C) before a batch's [q]: an honest brick asks one at a time
MAX_TIME_US = 2**53  # a brick's clock is counted in whole microseconds that a float holds exactly (285 years)
NOTE_NUMBERS = ("frequency", "length_ms", "delay_ms", "repeats")
SOUND_TEXTS = ("args", "text", "wav_file", "espeak_opts", "channel")
TEXT_CHARS = 500  # of each text of a sound that is kept
MATCH_ITEMS = 64  # attributes (and texts for each) a search for devices may name: python-ev3dev2 names 1 or 2
END_TEXTS = {"type": 200, "message": 2_000, "file": 1_000, "traceback": 20_000}  # what an end's error keeps
SANDBOX_LAYERS = 64  # entries of a hello's sandbox report that are kept (a brick reports about a dozen)


class OverBudget(Exception):
    """The brick went past one of its run's budgets (results/trace.py): its run ends, the message says which."""


def _number(key: str, value) -> int | float | None:
    """A sound's number within its range (SOUND_NUMBERS), or None for anything that is not a finite number."""
    if type(value) not in (int, float) or value != value or abs(value) == math.inf:
        return None
    low, high = SOUND_NUMBERS[key]
    return type(low)(min(max(value, low), high))


def clean_note(note: dict) -> dict:
    """One note of a beep as the trace keeps it: its numbers (NOTE_NUMBERS) in range, and end_delay."""
    clean: dict = {}
    for key, value in note.items():
        if key in NOTE_NUMBERS:
            number = _number(key, value)
            if number is not None:
                clean[key] = number
        elif key == "end_delay":
            clean[key] = bool(value)
    return clean


def clean_sound(details: dict) -> dict:
    """A sound's details as the trace keeps them: known keys only, numbers finite and in range, texts
    short, at most NOTES_PER_SOUND notes, each a flat note (a note holds no notes of its own): a brick
    sends what it likes, and the renderer must not choke."""
    clean: dict = {}
    for key, value in details.items():
        if key in SOUND_NUMBERS:
            number = _number(key, value)
            if number is not None:
                clean[key] = number
        elif key in SOUND_TEXTS:
            if type(value) is str:
                clean[key] = value[:TEXT_CHARS]
        elif key == "end_delay":
            clean[key] = bool(value)
        elif key == "notes" and type(value) is list:
            clean[key] = [clean_note(note) for note in value[:NOTES_PER_SOUND] if type(note) is dict]
    return clean


def sound_played(kind: str, details: dict) -> tuple[int, float]:
    """What a clean sound plays, as a video renders it (timeline.sound_spans): (notes, a note's repeats
    each counting as one and a note of none as one; seconds of sound)."""
    if kind == "beep":
        notes, seconds = 0, 0.0
        for note in details.get("notes", ()):
            repeats = note.get("repeats", 1)
            notes += max(repeats, 1)
            seconds += repeats * note.get("length_ms", 200.0) / 1000
        return notes, seconds
    if kind in ("speak", "play_file"):
        return 0, details.get("duration", 0.0)
    return 0, 0.0


THREADS_SAID = 64  # threads whose place a brick may say, at most


def said_threads(how) -> list | None:
    """The `threads` of a brick's end message, checked: [thread name, file, line] each, a few at most."""
    threads = how.get("threads") if type(how) is dict else None
    if type(threads) is not list:
        return None
    kept = [
        [item[0][:100], item[1][:1000], item[2]]
        for item in threads[:THREADS_SAID]
        if type(item) is list
        and len(item) == 3
        and type(item[0]) is str
        and type(item[1]) is str
        and type(item[2]) is int
    ]
    return kept or None


def clean_end(how: dict) -> dict:
    """What is kept of a brick's end message: its time, status and error, the texts cut short, and where
    its program's threads were (said_threads), for a run that did not end by itself."""
    status = how.get("status")
    error = how.get("error")
    kept: dict = {"t_us": how.get("t_us"), "status": status[:50] if type(status) is str else None}
    if type(error) is dict:
        report: dict = {
            key: error[key][:limit] for key, limit in END_TEXTS.items() if type(error.get(key)) is str
        }
        for key in ("line", "t_s"):
            if type(error.get(key)) in (int, float):
                report[key] = error[key]
        if error.get("compiling") is True:  # the brick could not compile the program (simulator/run.py)
            report["compiling"] = True
        kept["error"] = report
    else:
        kept["error"] = None
    threads = said_threads(how)
    if threads:
        kept["threads"] = threads
    return kept


DEBUG_TEXT = 2000  # characters of a debugger event's text
DEBUG_ITEMS = 64  # frames, breakpoints or threads in a debugger event
DEBUG_VARIABLES = 200  # names of a scope in a debugger event


def clean_debug_event(event) -> dict:
    """What is kept of an event of a brick's debugger (brick/debugger.py): texts and numbers only, short."""
    if type(event) is not dict:
        return {"event": "error", "message": "the brick's debugger sent no event"}

    def place(item) -> dict:
        item = item if type(item) is dict else {}
        kept = {k: str(item.get(k, ""))[:DEBUG_TEXT] for k in ("file", "function", "source", "thread")}
        line = item.get("line")
        return {**kept, "line": line if type(line) is int else 0}

    kept: dict = {"event": str(event.get("event", ""))[:50]}
    for key in ("reason", "text", "message"):
        if key in event:
            kept[key] = str(event[key])[:DEBUG_TEXT]
    if event.get("event") == "stopped":
        kept.update(place(event))
        kept["t_us"] = event["t_us"] if type(event.get("t_us")) is int else 0
    for key in ("frames", "breakpoints"):
        if type(event.get(key)) is list:
            kept[key] = [place(item) for item in event[key][:DEBUG_ITEMS]]
    if type(event.get("threads")) is list:
        kept["threads"] = [str(name)[:100] for name in event["threads"][:DEBUG_ITEMS]]
    if type(event.get("variables")) is list:
        kept["variables"] = [
            {k: str(item.get(k, ""))[:DEBUG_TEXT] for k in ("name", "value", "type")}
            for item in event["variables"][:DEBUG_VARIABLES]
            if type(item) is dict
        ]
    kept["error"] = event.get("error") is True
    return kept


def clean_hello(info: dict) -> dict:
    """What is kept of a brick's hello: its protocol, Python, and sandbox report (layer -> text), short."""
    kept: dict = {key: info[key] for key in ("protocol",) if type(info.get(key)) is int}
    if type(info.get("python")) is str:
        kept["python"] = info["python"][:200]
    sandbox = info.get("sandbox")
    if type(sandbox) is dict:
        kept["sandbox"] = {
            str(layer)[:100]: str(text)[:TEXT_CHARS] for layer, text in list(sandbox.items())[:SANDBOX_LAYERS]
        }
    return kept


class NoButtonPress(RuntimeError):
    """The program waits for a button that no scripted press will ever push."""


class BrickPort:
    """One brick as the simulator sees it: a robot, a connection, a queue of ops, and what the brick has
    used of its run's budgets (results/trace.py)."""

    def __init__(self, index: int, robot, channel, trace, presses: list, echo: list | None = None) -> None:
        """echo: a list that printed lines are added to, for the session to show in time order."""
        self.index = index
        self.robot = robot
        self.brick: Brick = robot.brick
        self.channel = channel
        self.trace = trace
        self.presses = presses
        self.echo = echo
        self.queue: deque = deque()
        self.keys: list[tuple] = []  # key -> (device or None, attribute, error if unknown)
        self._named: set[tuple[str, str, str]] = set()  # the (class, device, attribute) the keys name
        self._direct: dict[int, object] = {}  # key -> its device's writer, for writes that are nothing more
        self.subscribed: list[int] = []
        self._subscribed: set[int] = set()
        self._live_readers: list = []  # the subscribed attributes' readers, in the same order
        self.marker: int | None = None  # a tick the brick passed that the world has not reached
        # a quiet wait (op "u"): (its last tick, the watched value's place in a snapshot, the value the brick
        # waits to change); the session looks at each snapshot for it (wakes) and sends only the one it wakes at
        self.quiet: tuple[int, int, object] | None = None
        self.snapped: tuple[int, list] = (-1, [])  # the last snapshot taken: its label and values
        self.declared = 0  # the last tick marker applied: the brick's clock is past it
        self.time_us = 0  # the brick's clock as far as the simulator knows
        self.time_limit_us: int | None = None  # the run's (the session says): no clock earns ops past it
        self._end: dict | None = None  # the end message (what is kept of it), or why the brick is gone
        self._gone: str | None = None  # the brick broke the protocol, a budget, or died
        # whether either is set: kept by their setters, an attribute because the session asks it a dozen
        # times a tick for each brick (a property cost 80 ns each time)
        self.finished = False
        self._hello: dict | None = None
        self.volume = 100
        # how much of its budgets the brick has used
        self.ops = 0
        self.printed_lines = 0
        self.printed_bytes = 0
        self.events = 0  # recorded sounds, LED changes, LCD frames
        self.lcd_frames = 0
        self.notes = 0
        self.sound_s = 0.0
        self.dropped_lines = 0  # (none since printing has a budget: kept for the run's result)
        self.dropped_events = 0  # LCD draws within a refresh past LCD_DRAWS_PER_REFRESH (their last is kept)
        self._leds: dict | None = None  # the LEDs as last recorded
        # the LCD: the last draw's event, the frame it shows, and the refresh that frame was kept in; and the
        # refresh of the last draw, with how many draws were events in it
        self._screen: tuple[list, int, int] | None = None
        self._draws = (-1, 0)
        # real seconds the simulator waited on this brick, or applied its ops, since its clock last moved
        # (or the world let it go on): the session stops it as hung past hang_after_s (rule: docs/protocol.md)
        self.stalled_s = 0.0
        self.debugger = None  # the front end a stopped program's debugger asks (event -> command), if any
        self.debugged = False  # it asked since the session last looked: a stop is not a hang
        self._answers: list = []  # answers to the ops of the batch being applied
        self.broken = False  # a send failed: the brick is gone once what it sent is applied
        self.mailboxes = None  # the session's Bluetooth between bricks (mailboxes.py), once it has one

    # What is kept of the brick's first and last words: what the result reads of them, cut short.
    @property
    def hello(self) -> dict | None:
        return self._hello

    @hello.setter
    def hello(self, info: dict | None) -> None:
        self._hello = clean_hello(info) if type(info) is dict else None

    @property
    def end(self) -> dict | None:
        return self._end

    @end.setter
    def end(self, how: dict | None) -> None:
        self._end = clean_end(how) if type(how) is dict else None
        self.finished = self._end is not None or self._gone is not None

    @property
    def gone(self) -> str | None:
        """Why the brick is out of the run (broke the protocol, a budget, died, hung, stopped), if it is."""
        return self._gone

    @gone.setter
    def gone(self, why: str | None) -> None:
        self._gone = why
        self.finished = self._end is not None or why is not None

    def send(self, message: list) -> None:
        """Send to the brick; a brick that is gone is noticed when its last messages are applied."""
        if not self.broken:
            try:
                self.channel.send(message)
            except ProtocolError:
                self.broken = True

    # ------------------------------------------------------------ receiving
    def accept(self, message: list) -> None:
        """Queue what a message brings; OverBudget when the brick has sent more ops than its clock allows."""
        kind = message[0]
        if kind == "ops" and len(message) == 2 and type(message[1]) is list:
            ops = message[1]
            self.ops += len(ops)
            clock_us = self.time_us if self.time_limit_us is None else min(self.time_us, self.time_limit_us)
            if self.ops > OPS_BURST + OPS_PER_SECOND * clock_us // 1_000_000:
                raise OverBudget(
                    f"the program sent more than {OPS_BURST:,} operations and {OPS_PER_SECOND:,} a second of "
                    "its clock (OPS_PER_SECOND): it kept the simulator busy while its clock stood still"
                )
            self.queue.extend(ops)
        elif kind == "end" and len(message) == 2 and type(message[1]) is dict:
            self.queue.append(["end", message[1]])
        else:
            raise ProtocolError(f"unexpected message {str(kind)[:50]!r}")

    # ------------------------------------------------------------- applying
    def run_ops(self, world_us: int) -> None:
        """Apply queued ops until a tick marker ahead of the world (kept in self.marker) or the queue's end.

        Raises ProtocolError for what is not the protocol and OverBudget past a budget; anything else it
        raises is the simulator's own failure (the session ends this brick for it, and says so)."""
        queue = self.queue
        if not queue or self.marker is not None or self.finished:
            return
        direct = self._direct
        while queue:
            op = queue.popleft()
            if type(op) is not list or not op:
                raise ProtocolError("an op must be a non-empty JSON array")
            kind = op[0]
            if kind == "w":  # the hot path: a write the brick checked against the attribute's rule (a
                # value the device refuses is ignored: only a lying brick sends one)
                if len(op) == 3 and type(op[1]) is int:
                    writer = direct.get(op[1])
                    value = op[2]
                    if writer is not None and type(value) is str:
                        try:
                            writer(value)
                        except OSError:
                            pass
                        continue
                self._write_op(op)
            elif kind == "t":
                tick = op[1] if len(op) == 2 else None
                if type(tick) is not int or tick < self.time_us or tick < world_us or tick > MAX_TIME_US:
                    raise ProtocolError(f"tick marker {str(tick)[:30]} goes back in time")
                self.time_us = self.declared = tick
                if tick > world_us:
                    self.marker = tick
                    return
            elif kind == "u":
                if self._quiet(op, world_us):
                    return
            elif kind == "p":
                self._print(op)
            elif kind == "@":
                if len(op) != 2:
                    raise ProtocolError("a heartbeat is [@, t_us], and time does not go back")
                self._at(op[1])
            elif kind == "k":
                self._define(op)
            elif kind == "R":
                self._answer(self._subscribe(op))
            elif kind == "W":
                self._answer(self._checked_write(op))
            elif kind == "c":
                self._call(op, answer=False)
            elif kind == "C":
                self._answer(self._call(op, answer=True))
            elif kind == "q":
                answers, self._answers = self._answers, []
                self.send(["reply", answers, self.values()])
            elif kind == "end":
                if len(op) != 2:
                    raise ProtocolError("end carries a dict")
                self._finish(op[1])
                return
            else:
                raise ProtocolError(f"unknown op {str(kind)[:50]!r}")

    def _quiet(self, op: list, world_us: int) -> bool:
        """["u", first, last, key, value]: the brick's clock passes the ticks from first to last, as long as
        the key's value in each tick's snapshot is `value`.  The first tick's snapshot is taken already (the
        brick looks at it itself): where it differs, this is a tick marker at first; else the brick is quiet
        until the session wakes it (wakes).  True when the world must reach first before more is applied."""
        if len(op) != 5 or not all(type(x) is int for x in op[1:4]):
            raise ProtocolError("a quiet wait is [u, first tick, last tick, key, value]")
        first, last, key, value = op[1], op[2], op[3], op[4]
        if first < self.time_us or first <= world_us or last < first or last > MAX_TIME_US:
            raise ProtocolError(f"quiet wait from {first} to {str(last)[:30]} goes back in time")
        if key not in self._subscribed:
            raise ProtocolError("a quiet wait watches a value the brick reads in its snapshots")
        at = self.subscribed.index(key)
        label, values = self.snapped
        if label != first or at >= len(values):
            raise ProtocolError("a quiet wait starts at the tick of the last snapshot, on a value in it")
        self.time_us = self.declared = first
        if values[at] == value and first < last:
            self.quiet = (last, at, value)
            self.marker = last
        else:
            self.marker = first
        return True

    def wakes(self, label_us: int) -> bool:
        """A quiet brick, after the world's tick before label_us: the snapshot is taken (as for a brick that
        waits tick by tick, so sensors are sampled at the same ticks); sent, and True, if the watched value
        changed in it or label_us is the wait's last tick."""
        values = self.values()
        self.snapped = (label_us, values)
        last, at, value = self.quiet
        if label_us < last and values[at] == value:
            return False
        self.quiet = None
        self.time_us = self.declared = self.marker = label_us
        self.send(["snap", label_us, values])
        return True

    def _answer(self, answer) -> None:
        if len(self._answers) >= PENDING_REQUESTS:
            raise ProtocolError(f"more than {PENDING_REQUESTS} requests in a batch without its [q]")
        self._answers.append(answer)

    def _write_op(self, op: list) -> None:
        """A write off the hot path: one whose time is recorded (LEDs), or one to check in full."""
        if len(op) == 4:
            self._at(op[3])
        elif len(op) != 3:
            raise ProtocolError("a write is [w, key, value] or [w, key, value, t_us]")
        key, value = op[1], op[2]
        if type(key) is not int or not 0 <= key < len(self.keys):
            raise ProtocolError(f"op {op[:1]} names an undefined key")
        if type(value) is not str:
            raise ProtocolError("a written value is text")
        self._apply_write(key, value)

    def _key(self, op: list, at: int = 1):
        key = op[at] if len(op) > at else None
        if type(key) is not int or not 0 <= key < len(self.keys):
            raise ProtocolError(f"op {op[:1]} names an undefined key")
        return self.keys[key]

    def _define(self, op: list) -> None:
        if len(op) != 5 or type(op[1]) is not int or op[1] != len(self.keys):
            raise ProtocolError("keys must be defined in order, 0, 1, 2, ...")
        if len(self.keys) >= KEYS:
            raise OverBudget(f"the program named more than {KEYS:,} device attributes (KEYS)")
        _, _, class_name, device_name, attribute = op
        if not all(type(x) is str for x in (class_name, device_name, attribute)):
            raise ProtocolError("a key names a class, a device and an attribute (texts)")
        if max(len(class_name), len(device_name), len(attribute)) > NAME_CHARS:  # kept: not the name
            self.keys.append((None, "", [errno.ENAMETOOLONG, os.strerror(errno.ENAMETOOLONG)]))
            return
        where = (class_name, device_name, attribute)
        if where in self._named:
            raise ProtocolError("each key names another attribute: this one has a key already")
        self._named.add(where)
        try:
            device = self.brick.device(class_name, device_name)
        except OSError as err:
            self.keys.append((None, attribute, [err.errno, err.strerror or str(err)]))
            return
        self.keys.append((device, attribute, None))
        writer = device.writers.get(attribute)
        if writer is not None and device.sysfs_class != "leds":  # an LED's writes are events too
            self._direct[op[1]] = writer

    def _read(self, key: int):
        device, attribute, error = self.keys[key]
        if error is not None:
            return error
        reader = device.readers.get(attribute)
        try:
            return reader() if reader is not None else device.read(attribute)
        except OSError as err:
            return [err.errno or errno.EIO, err.strerror or str(err)]

    def values(self) -> list:
        """Every subscribed attribute's value now, in the order the brick first read them."""
        try:
            return [reader() for reader in self._live_readers]
        except OSError:  # one of them fails: each with its own error
            read = self._read
            return [read(key) for key in self.subscribed]

    def _subscribe(self, op: list) -> list:
        """A read that wants an answer: [how the value changes, the value now]; a value that changes with
        the world from now on comes in every snapshot and reply."""
        device, attribute, error = self._key(op)
        key = op[1]
        if error is not None or attribute in device.constants or attribute not in device.readers:
            kind = "constant"
        elif attribute in device.settings:
            kind = "setting"
        else:
            kind = "live"
            if key not in self._subscribed:
                self._subscribed.add(key)
                self.subscribed.append(key)
                self._live_readers.append(device.readers[attribute])
        return [kind, self._read(key)]

    def _apply_write(self, key: int, value) -> list | None:
        device, attribute, error = self.keys[key]
        if error is not None:
            return error
        if type(value) is not str:
            raise ProtocolError("a written value is text")
        writer = device.writers.get(attribute)
        try:
            if writer is None:
                device.write(attribute, value)  # raises the right error
            else:
                writer(value)
        except OSError as err:
            return [err.errno or errno.EIO, err.strerror or str(err)]
        if device.sysfs_class == "leds":
            leds = {n: led.brightness for n, led in self.brick.leds.items()}
            if leds != self._leds:  # an LED change: writing what an LED shows already changes nothing
                self._leds = leds
                self._event(self.time_us / 1e6, "leds", leds)
        return None

    def _event(self, t_s: float, kind: str, data) -> None:
        """Record an event in the trace; OverBudget past EVENTS of this brick's."""
        if self.events >= EVENTS:
            raise OverBudget(
                f"the program made more than {EVENTS:,} sounds, LED changes and LCD frames (EVENTS)"
            )
        self.events += 1
        self.trace.add_event(t_s, self.index, kind, data)

    def _checked_write(self, op: list) -> list:
        device, attribute, _ = self._key(op)
        error = self._apply_write(op[1], op[2] if len(op) > 2 else None)
        rule = device.write_rules.get(attribute) if device is not None else None
        return [error, rule]

    def _at(self, t_us) -> None:
        if type(t_us) is not int or t_us < self.time_us or t_us > MAX_TIME_US:
            raise ProtocolError("time goes back (or past 2**53 µs)")
        self.time_us = t_us

    def _print(self, op: list) -> None:
        if len(op) != 4 or type(op[2]) is not str or type(op[3]) is not str:
            raise ProtocolError("a printed line is [p, t_us, stream, text]")
        self._at(op[1])
        stream = "stderr" if op[2] == "stderr" else "stdout"
        text = op[3]
        self.printed_lines += 1
        self.printed_bytes += len(text) if text.isascii() else len(text.encode("utf-8", "surrogatepass"))
        if self.printed_lines > PRINTED_LINES:
            raise OverBudget(f"the program printed more than {PRINTED_LINES:,} lines (PRINTED_LINES)")
        if self.printed_bytes > PRINTED_BYTES:
            raise OverBudget(f"the program printed more than {PRINTED_BYTES / 1e6:g} MB (PRINTED_BYTES)")
        if len(text) > PRINTED_LINE_CHARS:
            text = text[:PRINTED_LINE_CHARS] + f" ... ({len(op[3]) - PRINTED_LINE_CHARS} more characters)"
        line = OutputLine(self.time_us / 1e6, self.index, stream, text)
        self.trace.add_output(line)
        if self.echo is not None:
            self.echo.append(line)

    def _call(self, op: list, answer: bool):
        if len(op) != 4 or type(op[2]) is not str or type(op[3]) is not list:
            raise ProtocolError("a call is [c, t_us, feature, [args]]")
        self._at(op[1])
        feature, args = op[2], op[3]
        try:
            result = self._feature(feature, args)
        except NoButtonPress as err:
            return {"error": ["NoButtonPress", str(err)]}
        except (TypeError, ValueError, KeyError, IndexError) as err:
            return {"error": ["RuntimeError", f"bad call to {feature[:50]}: {str(err)[:200]}"]}
        return result if answer else None

    def _feature(self, feature: str, args: list):
        now_s = self.time_us / 1e6
        if feature == "devices":
            class_name, pattern, match = args
            if type(class_name) is not str or type(pattern) is not str or type(match) is not dict:
                raise TypeError("devices takes a class, a pattern and a dict")
            if max(len(class_name), len(pattern)) > NAME_CHARS or len(match) > MATCH_ITEMS:
                return []  # (no device has so long a name, nor so many attributes)
            for wanted in match.values():
                if type(wanted) is list and len(wanted) > MATCH_ITEMS:
                    raise ValueError(f"at most {MATCH_ITEMS} texts to look for in an attribute")
            return self.brick.list_device_names(class_name, pattern, match)
        if feature == "sound":
            kind, details = str(args[0])[:50], clean_sound(dict(args[1]))
            if kind == "get_volume":
                return self.volume
            notes, seconds = sound_played(kind, details)
            self.notes += notes
            self.sound_s += seconds
            if self.notes > SOUND_NOTES:
                raise OverBudget(f"the program's beeps held more than {SOUND_NOTES:,} notes (SOUND_NOTES)")
            if self.sound_s > SOUND_SECONDS:
                raise OverBudget(f"the program played more than {SOUND_SECONDS:g} s of sound (SOUND_SECONDS)")
            if kind == "set_volume":
                self.volume = details.get("pct", 100)
            elif details.get("duration"):
                tick_s = self.trace.tick_s
                self.robot.sound_until_tick = int((now_s + float(details["duration"])) // tick_s) + 1
            self._event(now_s, "sound", {"kind": kind, **details})
            return None
        if feature == "display":
            pixels = bytes.fromhex(args[0])
            if len(pixels) != LCD_BYTES:
                raise ValueError(f"an LCD frame has {LCD_BYTES} bytes")
            self._lcd(now_s, pixels)
            return None
        if feature == "debug":  # the program stopped in its brick's debugger: the front end says what next
            if self.debugger is None:  # (nobody debugs: grading, serving; a brick that asks is no less hung)
                return {"cmd": "continue"}
            self.debugged = True
            return self.debugger(clean_debug_event(args[0]))
        if feature == "buttons":
            pressed = [p.button for p in self.presses if p.down_at(now_s)]
            if (
                args
                and args[0] == "wait"
                and not pressed
                and all(p.at_s + p.hold_s <= now_s for p in self.presses)
            ):
                raise NoButtonPress(
                    "the program waits for a button press, but no press is scripted from now on: "
                    "run with --press enter@2.0 (BUTTON@SECONDS), or add `buttons: [enter@2.0]` to the world file"
                )
            return pressed
        if feature == "mailbox" and self.mailboxes is not None:  # pybricks.messaging (mailboxes.py)
            return self.mailboxes.call(self, args)
        raise ValueError(f"no feature {feature[:50]!r}")

    def _lcd(self, now_s: float, pixels: bytes) -> None:
        """Record a draw of the LCD as the EV3's screen shows it: a new picture at most once a refresh
        (LCD_REFRESH_US).  A picture like the last one is not kept again; one drawn within the refresh of
        the last picture kept replaces it (LCD_FRAMES counts the pictures kept).  The first
        LCD_DRAWS_PER_REFRESH draws within a refresh are events of their own; a later one moves the last."""
        refresh = self.time_us // LCD_REFRESH_US
        frames = self.trace.lcd_frames
        screen = self._screen
        if screen is not None and frames[screen[1]] == pixels:
            frame, kept_in = screen[1], screen[2]
        elif screen is not None and screen[2] == refresh:
            frame, kept_in = screen[1], refresh
            frames[frame] = pixels  # (only draws of this refresh show it)
        else:
            if self.lcd_frames >= LCD_FRAMES:
                raise OverBudget(
                    f"the program drew more than {LCD_FRAMES:,} different LCD frames (LCD_FRAMES)"
                )
            self.lcd_frames += 1
            frame, kept_in = self.trace.add_lcd_frame(pixels), refresh
        drawn_in, draws = self._draws
        if screen is not None and drawn_in == refresh and draws >= LCD_DRAWS_PER_REFRESH:
            event = screen[0]
            event[0], event[3]["frame"] = now_s, frame
            self.dropped_events += 1
        else:
            self._event(now_s, "lcd", {"frame": frame})
            event = self.trace.events[-1]
            self._draws = (refresh, draws + 1 if drawn_in == refresh else 1)
        self._screen = (event, frame, kept_in)

    def _finish(self, how) -> None:
        if type(how) is not dict:
            raise ProtocolError("end carries a dict")
        t = how.get("t_us")
        if type(t) is not int or t < self.time_us or t > MAX_TIME_US:
            raise ProtocolError("the end goes back in time")
        self.time_us = t
        self.end = how

    # ------------------------------------------------------------- snapshots
    def snapshot(self, label_us: int) -> None:
        """Send the values now, to serve the brick's reads from label_us for one tick."""
        values = self.values()
        self.snapped = (label_us, values)
        self.send(["snap", label_us, values])
