"""A simulated EV3 brick: the robot's devices as the ev3dev drivers list them under /sys/class.

Motors are tacho-motor/motor0.., sensors lego-sensor/sensor0.. in port order,
plus the four status LEDs and the battery.  Finding devices follows
python-ev3dev2's rule: the name matches a glob, and every requested
attribute contains the requested text (or one of a list of texts).
"""

from __future__ import annotations

import errno
import fnmatch
import re

from .brick_parts import Battery, Led
from .device import Device

LED_NAMES = (
    "led0:red:brick-status",
    "led1:red:brick-status",
    "led0:green:brick-status",
    "led1:green:brick-status",
)


class Brick:
    """One robot's devices by sysfs class and device name."""

    def __init__(self, motors: list[Device], sensors: list[Device]) -> None:
        self.classes: dict[str, dict[str, Device]] = {
            "tacho-motor": {f"motor{i}": d for i, d in enumerate(motors)},
            "lego-sensor": {f"sensor{i}": d for i, d in enumerate(sensors)},
            "leds": {name: Led(name) for name in LED_NAMES},
            "power_supply": {"lego-ev3-battery": Battery()},
        }
        self.leds = self.classes["leds"]

    def device(self, class_name: str, name: str) -> Device:
        try:
            return self.classes[class_name][name]
        except KeyError:
            raise OSError(errno.ENODEV, f"No such device: /sys/class/{class_name}/{name}") from None

    def list_device_names(self, class_name: str, name_pattern: str, match: dict) -> list[str]:
        # (compiled here, through re's small cache: fnmatch's own keeps 32768 patterns a brick may choose)
        matches = re.compile(fnmatch.translate(name_pattern)).match
        found = []
        for name, device in self.classes.get(class_name, {}).items():
            if not matches(name):
                continue
            if all(self._matches(device, attribute, wanted) for attribute, wanted in match.items()):
                found.append(name)
        return found

    @staticmethod
    def _matches(device: Device, attribute: str, wanted) -> bool:
        try:
            value = device.read(attribute)
        except OSError:
            return False
        if isinstance(wanted, (list, tuple)):
            return any(value.find(w) >= 0 for w in wanted)
        return value.find(wanted) >= 0
