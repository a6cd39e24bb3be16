"""The simulator's end of one brick's connection: its ops applied to its robot's devices, in order.

A brick sends what its program did (see ev3sim2d/protocol/messages.py); the
port queues the ops and applies them when the session lets it: writes go to
the robot's devices, calls to the speaker, LCD and buttons, printed lines and
events to the trace.  Everything a brick sends is checked: it is a student's
program at the other end, and anything that is not the protocol (a wrong key,
time running backwards, a message too large) ends that brick's run.
"""

from __future__ import annotations

import errno
from collections import deque

from ..devices.brick import Brick
from ..protocol import ProtocolError
from ..results.trace import OutputLine

MAX_KEYS = 10_000
MAX_LINE = 2_000  # characters of one printed line that are kept
MAX_RECORDED_LINES = 5_000
MAX_EVENTS = 20_000  # sounds, LED changes, LCD frames of one brick (calls cost a brick no time)
MAX_LCD_FRAMES = 2_000
LCD_BYTES = 178 * 128
# what a sound's details may hold, and the range of each number (the renderer plays them back)
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
SOUND_TEXTS = ("args", "text", "wav_file", "espeak_opts", "channel")
MAX_NOTES = 100


def clean_sound(details: dict) -> dict:
    """A sound's details as the trace keeps them: known keys only, numbers finite and in range, texts
    short, at most MAX_NOTES notes; a brick sends what it likes, and the renderer must not choke."""
    clean: dict = {}
    for key, value in details.items():
        if key in SOUND_NUMBERS:
            if type(value) in (int, float) and value == value and abs(value) != float("inf"):
                low, high = SOUND_NUMBERS[key]
                clean[key] = type(low)(min(max(value, low), high))
        elif key in SOUND_TEXTS:
            if type(value) is str:
                clean[key] = value[:500]
        elif key == "end_delay":
            clean[key] = bool(value)
        elif key == "notes" and type(value) is list:
            clean[key] = [clean_sound(note) for note in value[:MAX_NOTES] if type(note) is dict]
    return clean


class NoButtonPress(RuntimeError):
    """The program waits for a button that no scripted press will ever push."""


class BrickPort:
    """One brick as the simulator sees it: a robot, a connection, a queue of ops."""

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
        self._direct: dict[int, object] = {}  # key -> its device's writer, for writes that are nothing more
        self.subscribed: list[int] = []
        self._live_readers: list = []  # the subscribed attributes' readers, in the same order
        self.marker: int | None = None  # a tick the brick passed that the world has not reached
        self.declared = 0  # the last tick marker applied: the brick's clock is past it
        self.time_us = 0  # the brick's clock as far as the simulator knows
        self.end: dict | None = None  # the end message, or why the brick is gone
        self.gone: str | None = None  # the brick broke the protocol or died
        self.volume = 100
        self.dropped_lines = 0
        self.events = 0  # recorded events (sounds, LEDs, LCD frames) and those dropped past the cap
        self.dropped_events = 0
        self.lcd_frames = 0
        self.last_heard = 0.0
        self.hello: dict | None = None
        self._answers: list = []  # answers to the ops of the batch being applied
        self.broken = False  # a send failed: the brick is gone once what it sent is applied

    def send(self, message: list) -> None:
        """Send to the brick; a brick that is gone is noticed when its last messages are applied."""
        if not self.broken:
            try:
                self.channel.send(message)
            except ProtocolError:
                self.broken = True

    @property
    def finished(self) -> bool:
        return self.end is not None or self.gone is not None

    # ------------------------------------------------------------ receiving
    def accept(self, message: list) -> None:
        """Queue what a message brings."""
        kind = message[0]
        if kind == "ops" and len(message) == 2 and type(message[1]) is list:
            self.queue.extend(message[1])
        elif kind == "end" and len(message) == 2 and type(message[1]) is dict:
            self.queue.append(["end", message[1]])
        else:
            raise ProtocolError(f"unexpected message {kind!r}")

    # ------------------------------------------------------------- applying
    def run_ops(self, world_us: int) -> None:
        """Apply queued ops until a tick marker ahead of the world (kept in self.marker) or the queue's end."""
        queue = self.queue
        if not queue or self.marker is not None or self.end is not None or self.gone is not None:
            return
        direct = self._direct
        while queue:
            op = queue.popleft()
            if type(op) is not list or not op:
                raise ProtocolError("an op must be a non-empty JSON array")
            kind = op[0]
            if kind == "w":  # the hot path: a write the brick checked against the attribute's rule (a
                # value the device refuses is ignored: only a lying brick sends one)
                if len(op) == 3:
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
                if type(tick) is not int or tick < self.time_us or tick < world_us:
                    raise ProtocolError(f"tick marker {tick!r} goes back in time")
                self.time_us = self.declared = tick
                if tick > world_us:
                    self.marker = tick
                    return
            elif kind == "p":
                self._print(op)
            elif kind == "@":
                if len(op) != 2 or type(op[1]) is not int or op[1] < self.time_us:
                    raise ProtocolError("a heartbeat is [@, t_us], and time does not go back")
            elif kind == "k":
                self._define(op)
            elif kind == "R":
                self._answers.append(self._subscribe(op))
            elif kind == "W":
                self._answers.append(self._checked_write(op))
            elif kind == "c":
                self._call(op, answer=False)
            elif kind == "C":
                self._answers.append(self._call(op, answer=True))
            elif kind == "q":
                answers, self._answers = self._answers, []
                self.send(["reply", answers, self.values()])
            elif kind == "end":
                self._finish(op[1])
                return
            else:
                raise ProtocolError(f"unknown op {kind!r}")

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
        if len(op) != 5 or op[1] != len(self.keys) or len(self.keys) >= MAX_KEYS:
            raise ProtocolError("keys must be defined in order, 0, 1, 2, ...")
        _, _, class_name, device_name, attribute = op
        if not all(type(x) is str for x in (class_name, device_name, attribute)):
            raise ProtocolError("a key names a class, a device and an attribute (texts)")
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
            if key not in self.subscribed:
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
            self._event(self.time_us / 1e6, "leds", {n: led.brightness for n, led in self.brick.leds.items()})
        return None

    def _event(self, t_s: float, kind: str, data) -> bool:
        """Record an event in the trace, up to MAX_EVENTS of this brick's; False when it is dropped."""
        if self.events >= MAX_EVENTS:
            self.dropped_events += 1
            return False
        self.events += 1
        self.trace.add_event(t_s, self.index, kind, data)
        return True

    def _checked_write(self, op: list) -> list:
        device, attribute, _ = self._key(op)
        error = self._apply_write(op[1], op[2] if len(op) > 2 else None)
        rule = device.write_rules.get(attribute) if device is not None else None
        return [error, rule]

    def _at(self, t_us) -> None:
        if type(t_us) is not int or t_us < self.time_us:
            raise ProtocolError("time goes back")
        self.time_us = t_us

    def _print(self, op: list) -> None:
        if len(op) != 4 or type(op[2]) is not str or type(op[3]) is not str:
            raise ProtocolError("a printed line is [p, t_us, stream, text]")
        self._at(op[1])
        stream = "stderr" if op[2] == "stderr" else "stdout"
        text = op[3]
        if len(text) > MAX_LINE:
            text = text[:MAX_LINE] + f" ... ({len(op[3]) - MAX_LINE} more characters)"
        if len(self.trace.output) >= MAX_RECORDED_LINES:
            self.dropped_lines += 1
            return
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
            return {"error": ["RuntimeError", f"bad call to {feature}: {err}"]}
        return result if answer else None

    def _feature(self, feature: str, args: list):
        now_s = self.time_us / 1e6
        if feature == "devices":
            class_name, pattern, match = args
            if type(match) is not dict:
                raise TypeError("match must be a dict")
            return self.brick.list_device_names(str(class_name), str(pattern), match)
        if feature == "sound":
            kind, details = str(args[0])[:50], clean_sound(dict(args[1]))
            if kind == "get_volume":
                return self.volume
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
            if self.lcd_frames < MAX_LCD_FRAMES and self.events < MAX_EVENTS:
                self.lcd_frames += 1
                self._event(now_s, "lcd", {"frame": self.trace.add_lcd_frame(pixels)})
            else:
                self.dropped_events += 1
            return None
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
        raise ValueError(f"no feature {feature!r}")

    def _finish(self, how) -> None:
        if type(how) is not dict:
            raise ProtocolError("end carries a dict")
        t = how.get("t_us")
        if type(t) is not int or t < self.time_us:
            raise ProtocolError("the end goes back in time")
        self.time_us = t
        self.end = how

    # ------------------------------------------------------------- snapshots
    def snapshot(self, label_us: int) -> None:
        """Send the values now, to serve the brick's reads from label_us for one tick."""
        self.send(["snap", label_us, self.values()])
