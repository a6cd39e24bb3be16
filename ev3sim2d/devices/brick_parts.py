"""The brick's own sysfs devices: the status LEDs and the battery."""

from __future__ import annotations

from .device import C_ULONG_MAX, Device, int_rule, invalid, parse_int

TRIGGERS = ("none", "timer", "heartbeat")  # the triggers the simulated brick lists


class Led(Device):
    """One colour of one brick status LED (class 'leds', e.g. led0:green:brick-status)."""

    sysfs_class = "leds"

    def __init__(self, name: str) -> None:
        super().__init__("", "")
        self.name = name
        self.brightness = 0
        self.trigger = "none"
        self.readers.update(
            brightness=lambda: str(self.brightness),
            max_brightness=lambda: "255",
            trigger=lambda: " ".join(f"[{t}]" if t == self.trigger else t for t in TRIGGERS),
        )
        self.writers.update(brightness=self._set_brightness, trigger=self._set_trigger)
        # led-class.c: brightness is parsed with kstrtoul and capped at max_brightness; a trigger must be
        # one the kernel lists (led_trigger_write: -EINVAL otherwise)
        self.write_rules.update(brightness=int_rule(0, C_ULONG_MAX), trigger=["choice", list(TRIGGERS)])
        self.constants = {"max_brightness"}
        self.settings = {"brightness", "trigger"}
        self.readers.pop("address")
        self.readers.pop("driver_name")

    def _set_brightness(self, value: str) -> None:
        self.brightness = min(parse_int(value, 0, C_ULONG_MAX), 255)

    def _set_trigger(self, value: str) -> None:
        trigger = value.strip()
        if trigger not in TRIGGERS:
            raise invalid(value)
        self.trigger = trigger


class Battery(Device):
    """The EV3's rechargeable battery (class 'power_supply'): plausible, steady figures."""

    sysfs_class = "power_supply"

    def __init__(self) -> None:
        super().__init__("", "")
        self.name = "lego-ev3-battery"
        self.readers.update(
            voltage_now=lambda: "7800000",
            current_now=lambda: "180000",
            voltage_max_design=lambda: "8400000",
            voltage_min_design=lambda: "6000000",
            technology=lambda: "Li-ion",
            type=lambda: "Battery",
            scope=lambda: "System",
        )
