"""The brick's end of the connection: ev3dev2._link's backend inside a brick process.

The shim reads and writes sysfs attributes; here they become protocol ops (see
ev3sim2d/protocol/messages.py) sent to the simulator, without a round trip for
each one:
- writes are checked here against the rule the simulator gave for the
  attribute (the first write of an attribute asks), then queued;
- when the brick's clock passes a tick, the queued ops go out with a tick
  marker, and the simulator steps the world to it and sends back a *snapshot*:
  the values of every attribute the program has read so far;
- a read is answered from the snapshot of the current tick, unless the program
  wrote to that device since (then the simulator is asked, with the queued
  ops, and answers with every value as it is now).
So a read gives exactly what the device would give at that virtual moment, as
if the program ran inside the simulator, and a busy loop costs one message
each way per tick.

Each access costs the virtual time the same access takes on a real EV3 running
python-ev3dev2: Python on the brick's 300 MHz ARM plus the sysfs file access,
about 2 ms for a read and 3 ms for a write (writes make the driver act).
Measured on real bricks, a two-sensor RGB line follower with python-ev3dev2
runs at about 30 loops a second (8 reads and 4 writes a loop: 28 ms here), and
a loop of 4 writes and 2 reads took 30-40 ms with an older binding.  What the
shim does for an access is in that cost; the program's own lines cost their
own time (cpu_time.py).

As its clock passes tick T the brick waits, if it must, for the snapshot of the
interval before (labelled T - tick, sent as the world passed T - 2 ticks: there
already, unless the program ran two ticks ahead of the world without reading),
so it runs at most two ticks ahead of the world even when it reads nothing, and
hears the simulator's stop (its time limit, a hang, Ctrl-C) at the same point
of the program in every run: where the program was is the same each time.
A poll (a wait for a motor's `state` to change, python-ev3dev2's and Pybricks'
waits for a move) need not hear of every tick: it tells the simulator the value
it waits on (a quiet wait, op "u"), and hears of the world again only at the
tick where the value changed, or at the poll's timeout (`poll`).
While the program's thread is stuck outside the simulation (a real lock, a
pipe), another thread may look (`stop_waiting`), so that the brick can still
say where it was.
"""

from __future__ import annotations

import errno
import time
from _thread import allocate_lock
from threading import get_ident

from ..protocol import ProtocolError
from .scheduler import RunOver, Scheduler

READ_US = 2_000  # reading one attribute (a sensor value, a motor's position or state)
WRITE_US = 3_000  # writing one attribute (a speed, a command, a mode)
FIND_US = 2_000  # looking a device up when it is constructed
# Reading the brick's buttons: python-ev3dev2 2.1.0's Button.buttons_pressed is one ioctl, then a loop over
# the six buttons (about 24 lines, 0.65 ms at cpu_time.LINE_US): about 1 ms.
BUTTONS_US = 1_000
# A mailbox request of pybricks.messaging (a lock, a dict, a socket's send): about 0.3 ms of MicroPython.
MAILBOX_US = 300

# A wait with no timeout is looked at by the simulator for at most this many ticks at a time (_quiet_until).
QUIET_TICKS = 100_000
HEARTBEAT_S = 0.5  # real seconds between two messages at most, while the clock moves
_perf_counter = time.perf_counter  # the real clock (the program's is virtual)


class OutsideTask(RuntimeError):
    """A device was used from a thread the brick does not schedule."""


class NoButtonPress(RuntimeError):
    """The program waits for a button that no scripted press will ever push."""


class RunStopped(RunOver):
    """The simulator ended the run (or went away): every task unwinds."""


def _invalid(value: str) -> OSError:
    return OSError(errno.EINVAL, f"Invalid argument: {value!r}")


def check_write(rule: list, value: str) -> None:
    """Raise the OSError the device would raise for this value (rules: see Device.write_rules)."""
    kind = rule[0]
    if kind == "int":
        try:
            number = int(str(value).strip())
        except ValueError:
            raise _invalid(value) from None
        low, high = rule[1], rule[2]
        if (low is not None and number < low) or (high is not None and number > high):
            raise _invalid(value)
    elif kind == "choice":
        if value.strip() not in rule[1]:
            raise _invalid(value)


class _NoConnection:
    """The connection as a process the program forked sees it: gone."""

    def send(self, message: list) -> None:
        raise ProtocolError("a process the program forked is not part of the run")

    def receive(self, timeout_s: float | None = None) -> list:
        raise ProtocolError("a process the program forked is not part of the run")


class BrickLink:
    """What ev3dev2._link calls during a run: device access in virtual time, over the protocol.

    Snapshots: the one labelled T serves reads while the brick's clock is in [T, T + tick); the
    simulator takes it when the world has run the tick before T, and sends it at once, so it is
    usually here before the brick needs it (the world steps while the program computes).  A
    device written since the snapshot's moment is *stale*: reading it asks the simulator.
    """

    def __init__(self, channel, scheduler: Scheduler) -> None:
        self.channel = channel
        self.scheduler = scheduler
        self.tick_us = scheduler.tick_us
        self._tasks = scheduler.by_thread
        self.keys: dict[tuple[str, str, str], int] = {}
        self.key_device: list[int] = []  # key -> device number
        self.devices: dict[tuple[str, str], int] = {}
        self.checked: dict[tuple[str, str, str], tuple] = {}  # (class, device, attribute) -> (key,
        # device number, rule, time-stamped) for the attributes whose writes are checked here
        self.position: dict[int, int] = {}  # key -> its place in a snapshot's values
        self.live_since: dict[int, int] = {}  # key -> the tick marker before the brick first read it
        self.fixed: dict[int, tuple] = {}  # key -> (value, the device's writes then; -1: for ever)
        self.writes: list[int] = []  # device -> how many times the program wrote to it
        self.values: list = []  # the values reads are answered from
        self.label = 0  # the interval the values serve (its first tick)
        self.declared = 0  # the last tick marker sent: the brick's clock is in [declared, declared + tick)
        self.ahead: tuple[int, list] | None = None  # a snapshot that arrived for a later interval
        self.heard_us = 0  # the label of the latest snapshot that arrived
        self.stale: set[int] = set()  # devices written since the moment of the values
        self.written: set[int] = set()  # devices written since the last tick marker
        self.ops: list = []
        self.stopped: str | None = None  # why the simulator ended the run
        self._reading = allocate_lock()  # held by whichever thread reads the connection
        self.early: list = []  # messages another thread read (stop_waiting), for the program's thread
        self.last_sent = _perf_counter()
        self.last_sent_us = 0  # the brick's clock when it last sent something
        self.quiet = True  # a poll may pass ticks without a hand-over each ("u"; the welcome's `quiet`)
        scheduler.on_progress = self.progress

    # ------------------------------------------------------------ plumbing
    def _key(self, class_name: str, device_name: str, attribute: str) -> int:
        where = (class_name, device_name, attribute)
        key = self.keys.get(where)
        if key is None:
            key = self.keys[where] = len(self.key_device)
            device = self.devices.get((class_name, device_name))
            if device is None:
                device = self.devices[(class_name, device_name)] = len(self.writes)
                self.writes.append(0)
            self.key_device.append(device)
            self.ops.append(["k", key, class_name, device_name, attribute])
        return key

    def _task(self) -> None:
        if get_ident() not in self._tasks:
            raise OutsideTask(
                "an EV3 device was used from a thread ev3sim2d does not run; "
                "start threads with threading or _thread inside the program"
            )

    def progress(self) -> None:
        """The clock moves between ticks (a program computing with short sleeps): now and then say so,
        so that the simulator does not take the brick for hung."""
        now_us = self.scheduler.now_us
        if now_us != self.last_sent_us and _perf_counter() - self.last_sent > HEARTBEAT_S:
            self.ops.append(["@", now_us])
            self.flush()

    def flush(self) -> None:
        """Send the queued ops (no answer wanted)."""
        if self.ops:
            self.last_sent = _perf_counter()
            self.last_sent_us = self.scheduler.now_us
            ops, self.ops = self.ops, []
            try:
                self.channel.send(["ops", ops])
            except ProtocolError as err:
                self._gone(str(err))

    def tick(self, tick_us: int) -> None:
        """The scheduler's clock passed tick_us (the last of the ticks it passed): the world may step."""
        self.ops.append(["t", tick_us])
        if tick_us == self.declared + self.tick_us:
            self.stale = self.written  # the new snapshot was taken before these writes
        else:
            self.stale = set()  # after a jump the snapshot is taken after every write so far
        self.written = set()
        self.declared = tick_us
        if self.ahead is not None and self.ahead[0] == tick_us:
            self.label, self.values = self.ahead
            self.ahead = None
        self.flush()
        while self.heard_us < tick_us - self.tick_us:  # (see the module's docstring)
            self._next_message()

    def output(self, t_us: int, stream: str, text: str) -> None:
        """A printed line, sent at once (so it is not lost if the program hangs afterwards)."""
        self.ops.append(["p", t_us, stream, text])
        self.flush()

    def detach(self) -> None:
        """In a process the program forked: it is not the brick (only the brick's own process runs in
        lockstep with the world), so it must never write to the connection it shares: from now on
        every use of it ends that process's program, as a connection that is gone does."""
        self.channel = _NoConnection()
        self.ops = []

    def _gone(self, why: str) -> None:
        self.stopped = self.stopped or why
        self.scheduler.stop("stopped")
        raise RunStopped()

    def _next_message(self) -> list:
        if self.early:
            message = self.early.pop(0)
        else:
            with self._reading:
                try:
                    message = self.channel.receive()
                except ProtocolError as err:
                    self._gone(str(err))
        self._take(message)
        return message

    def _take(self, message: list) -> None:
        """A snapshot kept for its interval; the simulator's stop ends the run (RunStopped)."""
        kind = message[0]
        if kind == "snap":
            label = message[1]
            self.heard_us = max(self.heard_us, label)
            if label == self.declared:
                if self.label != label:
                    self.label, self.values = label, message[2]
            elif label > self.declared:
                self.ahead = (label, message[2])
        elif kind == "stop":
            self._gone(_why_stopped(message))
        elif kind != "reply":
            self._gone(f"unexpected message {kind!r} from the simulator")

    def stop_waiting(self) -> str | None:
        """(From a thread other than the program's, while the program's clock stands still and it reads
        nothing from the simulator.)  Why the simulator stopped the run, if it has; None if it has not,
        or if the program's thread is reading.  The messages read wait, in order, for the program's
        thread (self.early)."""
        if not self._reading.acquire(False):
            return None
        try:
            while True:
                try:
                    message = self.channel.pending()
                except ProtocolError as err:
                    return str(err)
                if message is None:
                    return None
                self.early.append(message)
                if message[0] == "stop":
                    return _why_stopped(message)
        finally:
            self._reading.release()

    def ask(self, ops: list) -> list:
        """Send the queued ops and these, which want answers; wait for the answers (and every value now)."""
        self.ops.extend(ops)
        self.ops.append(["q"])
        self.flush()
        while True:
            message = self._next_message()
            if message[0] == "reply":
                self.values = message[2]
                self.label = self.declared
                self.stale = set()
                return message[1]

    # --------------------------------------------------------- the backend
    def _value(self, class_name: str, device_name: str, attribute: str):
        """The attribute's value now (text, or [errno, message] for a failing read)."""
        key = self.keys.get((class_name, device_name, attribute))
        if key is None:
            key = self._key(class_name, device_name, attribute)
        fixed = self.fixed.get(key)
        if fixed is not None and (fixed[1] < 0 or fixed[1] == self.writes[self.key_device[key]]):
            return fixed[0]
        at = self.position.get(key)
        if at is None:
            return self._ask_value(key)
        while self.label != self.declared:
            self._next_message()
        if at < len(self.values) and self.key_device[key] not in self.stale:
            return self.values[at]
        self.ask([])
        return self.values[at]

    def _ask_value(self, key: int):
        """Ask for one value, and learn how it changes (a constant, a setting, or with the world)."""
        kind, value = self.ask([["R", key]])[0]
        if kind == "live":
            self.position[key] = len(self.position)
            self.live_since[key] = self.declared  # (in the snapshots of the ticks after the next one)
        else:
            device = self.key_device[key]
            self.fixed[key] = (value, -1 if kind == "constant" else self.writes[device])
        return value

    def read(self, class_name: str, device_name: str, attribute: str) -> str:
        self._task()
        value = self._value(class_name, device_name, attribute)
        self.scheduler.spend(READ_US)
        if type(value) is str:
            return value
        raise OSError(value[0], value[1])

    def write(self, class_name: str, device_name: str, attribute: str, value) -> None:
        self._task()
        if self.scheduler.frozen:
            raise RuntimeError("the program is stopped in the debugger: writing to the robot is refused")
        if not isinstance(value, str):
            value = bytes(value).decode("latin-1")
        known = self.checked.get((class_name, device_name, attribute))
        if known is not None:  # the hot path: an attribute whose rule is known
            key, device, rule, stamped = known
            self.writes[device] += 1
            self.written.add(device)
            self.stale.add(device)
            check_write(rule, value)
            self.ops.append(["w", key, value, self.scheduler.now_us] if stamped else ["w", key, value])
            self.scheduler.spend(WRITE_US)
            return
        key = self.keys.get((class_name, device_name, attribute))
        if key is None:
            key = self._key(class_name, device_name, attribute)
        device = self.key_device[key]
        self.writes[device] += 1
        self.written.add(device)
        self.stale.add(device)
        # an attribute written for the first time, or one whose writes the simulator checks each time
        error, rule = self.ask([["W", key, value]])[0]
        if rule is not None:
            self.checked[(class_name, device_name, attribute)] = (key, device, rule, class_name == "leds")
        if error is not None:
            raise OSError(error[0], error[1])
        self.scheduler.spend(WRITE_US)

    def poll(self, class_name: str, device_name: str, attribute: str, timeout_ms) -> None:
        """Wait until the attribute's value changes or timeout_ms passes (select.poll on a sysfs file).

        As scheduler.wait does, the value is looked at at each tick, in that tick's snapshot; where nothing
        else can happen meanwhile (see _quiet_until), the simulator looks at it instead ("u"), and the
        brick hears of the world again only at the tick where it changed, or at the last tick before the
        timeout: the same ticks, the same values, without a hand-over each tick.  (A hand-over, a message
        each way with the other side woken, costs 10-15 µs on one core and 60-70 µs across two on the
        2-core machines measured, as much as the world's tick of one robot: a wait of 100 ms saves ten.)"""
        self._task()
        before = self._value(class_name, device_name, attribute)
        timeout_us = None if timeout_ms is None else int(timeout_ms * 1000)
        scheduler = self.scheduler
        deadline = None if timeout_us is None else scheduler.now_us + timeout_us
        key = self.keys[(class_name, device_name, attribute)]
        while self._value(class_name, device_name, attribute) == before:  # (scheduler.wait's loop)
            now = scheduler.now_us
            if deadline is not None and now >= deadline:
                return
            last = self._quiet_until(key, deadline)
            if last is not None:
                self._quiet(key, before, last)
                continue
            step_to = scheduler.next_tick_us if deadline is None else min(scheduler.next_tick_us, deadline)
            scheduler.spend(max(step_to - now, 0) or self.tick_us)

    def _quiet_until(self, key: int, deadline: int | None) -> int | None:
        """The last tick to which the simulator may look at this key's value for the brick (None: not now):
        the value is live and in the snapshots, nothing was written since the last tick marker (so the next
        snapshot is the value now), no other task of the program is due before it, and it is two ticks
        away at least (one is no saving)."""
        scheduler = self.scheduler
        if not self.quiet or scheduler.frozen or scheduler.over or self.written or key in self.fixed:
            return None
        if (
            self.live_since.get(key, self.declared) >= self.declared
        ):  # (not live, or not in the next snapshot)
            return None
        if self.declared + self.tick_us != scheduler.next_tick_us:
            return None
        first = scheduler.next_tick_us
        if deadline is None:
            last = first + QUIET_TICKS * self.tick_us
        else:
            last = first + (deadline - first) // self.tick_us * self.tick_us
        ready = scheduler._ready
        if ready and ready[0][0] <= last:  # (another task is due: it runs first, as spend would let it)
            last = first + (ready[0][0] - 1 - first) // self.tick_us * self.tick_us
        if scheduler.limit_us is not None and last >= scheduler.limit_us:
            last = first + (scheduler.limit_us - 1 - first) // self.tick_us * self.tick_us
        return last if last > first else None

    def _quiet(self, key: int, before, last: int) -> None:
        """Pass the ticks from the next one to `last` without a hand-over at each: ["u", first, last, key,
        before] tells the simulator to look at the key's value in each tick's snapshot, and to send the
        snapshot of the first tick where it is not `before` (or of `last`); the brick's clock then lands on
        that tick, as scheduler.wait's would.  The first tick's snapshot is the one the simulator sends
        anyway: the brick looks at it itself."""
        first = self.declared + self.tick_us
        self.ops.append(["u", first, last, key, before])
        self.stale = set()  # (nothing was written since the last marker: _quiet_until)
        self.declared = first
        if self.ahead is not None and self.ahead[0] == first:
            self.label, self.values = self.ahead
            self.ahead = None
        self.flush()
        while self.label != first:
            self._next_message()
        landed = first
        if self.values[self.position[key]] == before and first < last:
            while self.ahead is None:  # (the next snapshot is the one of the tick it woke at)
                self._next_message()
            landed, self.values = self.ahead
            self.label = self.declared = self.heard_us = landed
            self.ahead = None
        self.scheduler.jump(landed)

    def list_device_names(self, class_name: str, name_pattern: str, match: dict) -> list[str]:
        self._task()
        names = self._call(True, "devices", [class_name, name_pattern, match])
        self.scheduler.spend(FIND_US)
        return list(names)

    def call(self, feature: str, *args):
        """Brick features beyond sysfs: the speaker, the buttons, the LCD."""
        self._task()
        if feature == "sound":
            kind = args[0]
            details = dict(args[1]) if len(args) > 1 else {}
            return self._call(kind == "get_volume", "sound", [kind, details])
        if feature == "display":
            pixels = args[0] if args else None
            if pixels is not None:
                self._call(False, "display", [bytes(pixels).hex()])
            return None
        if feature == "buttons":
            answer = self._call(True, "buttons", list(args[:1]))
            if not args:  # (["wait"] asks the simulator whether a press is to come: no EV3 does that)
                self.scheduler.spend(BUTTONS_US)
            return answer
        if feature == "mailbox":  # pybricks.messaging: Bluetooth between bricks (simulator/mailboxes.py)
            return self._mailbox(list(args))
        if feature == "debug":  # (brick/debugger.py: an event, answered by the front end's command)
            return self._call(True, "debug", [args[0]])
        raise ValueError(f"the simulated brick has no feature {feature!r}")

    def _mailbox(self, args: list):
        """A mailbox request; ["until", request...] asks again each tick (virtual time) until the answer is
        not None, as a blocked socket would wait."""
        if args and args[0] == "until":
            answers = [None]

            def answered() -> bool:
                answers[0] = self._call(True, "mailbox", args[1:])
                return answers[0] is not None

            self.scheduler.wait(answered, None)
            return answers[0]
        answer = self._call(True, "mailbox", args)
        self.scheduler.spend(MAILBOX_US)
        return answer

    def _call(self, answered: bool, feature: str, args: list):
        now = self.scheduler.now_us
        if not answered:
            self.ops.append(["c", now, feature, args])
            self.flush()  # an LCD frame is large: never let them pile up in the brick
            return None
        answer = self.ask([["C", now, feature, args]])[0]
        if isinstance(answer, dict) and "error" in answer:
            kind, message = answer["error"]
            raise (NoButtonPress if kind == "NoButtonPress" else RuntimeError)(message)
        return answer


def _why_stopped(message: list) -> str:
    return str(message[1]) if len(message) > 1 else "stopped"
