"""The simulator's side of the shim's link: a program's sysfs reads and writes, in virtual time.

Calls come from the program task holding the turn; they go to that task's
robot's brick, and each costs the virtual time the same access takes on a
real EV3 running python-ev3dev2: Python on the brick's 300 MHz ARM plus the
sysfs file access, about 2 ms for a read and 3 ms for a write (writes make
the driver act).  Measured on real bricks, a two-sensor RGB line follower
with python-ev3dev2 runs at about 30 loops a second (8 reads and 4 writes a
loop: 28 ms here), and a loop of 4 writes and 2 reads took 30-40 ms with an
older binding.  So a busy loop advances the clock as on the brick: the
one-sensor line follower in examples/ (2 reads, 4 writes) runs at about 60
loops a second.
"""

from __future__ import annotations

from threading import get_ident

from .scheduler import Scheduler
from .trace import Trace

READ_US = 2_000  # reading one attribute (a sensor value, a motor's position or state)
WRITE_US = 3_000  # writing one attribute (a speed, a command, a mode)
FIND_US = 2_000  # looking a device up when it is constructed


class OutsideTask(RuntimeError):
    """A device was used from a thread the simulator does not schedule."""


class NoButtonPress(RuntimeError):
    """The program waits for a button that no scripted press will ever push."""


class ShimLink:
    """The backend ev3dev2._link talks to during a run."""

    def __init__(self, scheduler: Scheduler, trace: Trace, robots: list, presses: list | None = None) -> None:
        self.scheduler = scheduler
        self.presses = list(presses or ())  # ButtonPress: scripted presses of the brick's buttons
        self.trace = trace
        self.robots = robots
        self._task_by_thread = scheduler.by_thread
        self.volume = {}  # robot index -> speaker volume, percent

    def _robot(self):
        task = self._task_by_thread.get(get_ident())
        if task is None:
            raise OutsideTask(
                "an EV3 device was used from a thread ev3sim2d does not run; "
                "start threads with threading or _thread inside the program"
            )
        return task.owner

    def _device(self, class_name: str, device_name: str):
        return self._robot().brick.device(class_name, device_name)

    def list_device_names(self, class_name: str, name_pattern: str, match: dict) -> list[str]:
        names = self._robot().brick.list_device_names(class_name, name_pattern, match)
        self.scheduler.spend(FIND_US)
        return names

    def read(self, class_name: str, device_name: str, attribute: str) -> str:
        try:
            device = self._task_by_thread[get_ident()].owner.brick.classes[class_name][device_name]
            value = device.readers[attribute]()
        except KeyError:
            value = self._device(class_name, device_name).read(attribute)  # raises the right error
        self.scheduler.spend(READ_US)
        return value

    def write(self, class_name: str, device_name: str, attribute: str, value: str | bytes) -> None:
        if not isinstance(value, str):
            value = bytes(value).decode("latin-1")
        try:
            device = self._task_by_thread[get_ident()].owner.brick.classes[class_name][device_name]
            writer = device.writers[attribute]
        except KeyError:
            self._device(class_name, device_name).write(attribute, value)  # raises the right error
        else:
            writer(value)
        if class_name == "leds":
            self._event("leds", {name: led.brightness for name, led in self._robot().brick.leds.items()})
        self.scheduler.spend(WRITE_US)

    def poll(self, class_name: str, device_name: str, attribute: str, timeout_ms) -> None:
        device = self._device(class_name, device_name)
        before = device.read(attribute)
        timeout_us = None if timeout_ms is None else int(timeout_ms * 1000)
        self.scheduler.wait(lambda: device.read(attribute) != before, timeout_us)

    def _event(self, kind: str, data: dict) -> None:
        self.trace.add_event(self.scheduler.now_s, self.robots.index(self._robot()), kind, data)

    def call(self, feature: str, *args):
        """Brick features beyond sysfs: the speaker, the buttons, the LCD; recorded in the trace."""
        if feature == "sound":
            kind, details = args[0], dict(args[1]) if len(args) > 1 else {}
            robot = self.robots.index(self._robot())
            if kind == "get_volume":
                return self.volume.get(robot, 100)
            if kind == "set_volume":
                self.volume[robot] = details.get("pct", 100)
            elif details.get("duration"):
                s = self.scheduler
                self._robot().sound_until_tick = int((s.now_us + details["duration"] * 1e6) // s.tick_us) + 1
            self._event("sound", {"kind": kind, **details})
            return None
        if feature == "display":
            pixels = args[0] if args else None
            if pixels is not None:
                self._event("lcd", {"frame": self.trace.add_lcd_frame(bytes(pixels))})
            return None
        if feature == "buttons":
            now = self.scheduler.now_s
            pressed = [p.button for p in self.presses if p.down_at(now)]
            if (
                args
                and args[0] == "wait"
                and not pressed
                and all(p.at_s + p.hold_s <= now for p in self.presses)
            ):
                raise NoButtonPress(
                    "the program waits for a button press, but no press is scripted from now on: "
                    "run with --press enter@2.0 (BUTTON@SECONDS), or add `buttons: [enter@2.0]` to the world file"
                )
            return [p.button for p in self.presses if p.down_at(now)]
        raise ValueError(f"the simulated brick has no feature {feature!r}")
