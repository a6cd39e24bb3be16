"""
A stand-in for the simulated brick, for testing the ev3dev2 shim.

``FakeBrick`` is an ``ev3dev2._link`` backend: its devices are dicts of
attribute strings, and it records every read, write and poll in ``log`` so a
test can assert exactly what the shim did.  It keeps a virtual clock that
``poll`` and ``sleep`` advance, so waits and timeouts run instantly.

An attribute may hold a list of values: each read takes the first one, and the
last one stays (a motor that runs, then stops: ``state=['running', '']``).

The same class also drives the real python-ev3dev2 in
``conformance/record_upstream_writes.py``, which is why it uses only the
standard library and JSON-friendly specs.
"""

import errno
import fnmatch

MOTOR_COMMANDS = "run-forever run-to-abs-pos run-to-rel-pos run-timed run-direct stop reset"


def tacho_motor(name, port, driver_name="lego-ev3-l-motor", max_speed=1050, count_per_rot=360, **attrs):
    """The spec of a tacho motor (large by default) on output ``port`` ('outA' ...)."""
    values = {
        "address": "ev3-ports:" + port,
        "driver_name": driver_name,
        "max_speed": str(max_speed),
        "count_per_rot": str(count_per_rot),
        "commands": MOTOR_COMMANDS,
        "stop_actions": "coast brake hold",
        "state": "",
        "position": "0",
        "speed": "0",
        "speed_sp": "0",
        "position_sp": "0",
        "time_sp": "0",
        "duty_cycle": "0",
        "duty_cycle_sp": "0",
        "polarity": "normal",
        "stop_action": "coast",
        "ramp_up_sp": "0",
        "ramp_down_sp": "0",
        "command": "",
        "hold_pid/Kp": "0",
        "hold_pid/Ki": "0",
        "hold_pid/Kd": "0",
        "speed_pid/Kp": "0",
        "speed_pid/Ki": "0",
        "speed_pid/Kd": "0",
    }
    values.update(attrs)
    return {"class": "tacho-motor", "name": name, "attrs": values}


def medium_motor(name, port, **attrs):
    return tacho_motor(name, port, driver_name="lego-ev3-m-motor", max_speed=1560, **attrs)


SENSOR_MODES = {
    "lego-ev3-color": "COL-REFLECT COL-AMBIENT COL-COLOR REF-RAW RGB-RAW COL-CAL",
    "lego-ev3-us": "US-DIST-CM US-DIST-IN US-LISTEN US-SI-CM US-SI-IN",
    "lego-ev3-gyro": "GYRO-ANG GYRO-RATE GYRO-FAS GYRO-G&A GYRO-CAL TILT-RATE TILT-ANG",
    "lego-ev3-touch": "TOUCH",
    "lego-ev3-ir": "IR-PROX IR-SEEK IR-REMOTE IR-REM-A IR-S-ALT IR-CAL",
}


def sensor(name, port, driver_name, mode=None, **attrs):
    """The spec of a lego-sensor on input ``port`` ('in1' ...); value0..7 default to '0'."""
    modes = SENSOR_MODES.get(driver_name, "")
    values = {
        "address": "ev3-ports:" + port,
        "driver_name": driver_name,
        "modes": modes,
        "mode": mode or (modes.split() or [""])[0],
        "commands": "",
        "decimals": "0",
        "num_values": "1",
        "units": "",
        "bin_data_format": "s8",
        "bin_data": "\x00",
        "command": "",
    }
    values.update({f"value{n}": "0" for n in range(8)})
    if driver_name == "lego-ev3-gyro":
        values["direct"] = ""
    values.update(attrs)
    return {"class": "lego-sensor", "name": name, "attrs": values}


def leds():
    """The four status LEDs of the EV3."""
    return [
        {
            "class": "leds",
            "name": name,
            "attrs": {
                "brightness": "0",
                "max_brightness": "255",
                "trigger": "[none] timer heartbeat default-on",
            },
        }
        for name in (
            "led0:red:brick-status",
            "led1:red:brick-status",
            "led0:green:brick-status",
            "led1:green:brick-status",
        )
    ]


def battery():
    return {
        "class": "power_supply",
        "name": "lego-ev3-battery",
        "attrs": {
            "current_now": "180000",
            "voltage_now": "7850000",
            "voltage_max_design": "9000000",
            "voltage_min_design": "6000000",
            "technology": "Li-ion",
            "type": "Battery",
        },
    }


def lego_port(name, port, mode="auto"):
    return {
        "class": "lego-port",
        "name": name,
        "attrs": {
            "address": "ev3-ports:" + port,
            "driver_name": "ev3-input-port",
            "modes": "auto nxt-analog nxt-color nxt-i2c other-uart ev3-analog ev3-uart other-i2c raw",
            "mode": mode,
            "set_device": "",
            "status": mode,
        },
    }


class FakeBrick:
    """An ev3dev2._link backend serving attributes from dicts and logging every access."""

    def __init__(self, devices=()):
        self.devices = {}
        self.log = []
        self.calls = []
        self.buttons = []
        self.volume = 100
        self.clock = 1000.0
        for spec in devices:
            self.add(spec)

    def add(self, spec):
        attrs = {
            key: list(value) if isinstance(value, list) else value for key, value in spec["attrs"].items()
        }
        self.devices[(spec["class"], spec["name"])] = attrs

    def attrs(self, class_name, name):
        return self.devices[(class_name, name)]

    # -- the virtual clock ------------------------------------------------
    def time(self):
        return self.clock

    def sleep(self, seconds):
        self.clock += max(seconds, 0)

    # -- the backend interface ----------------------------------------------
    def list_device_names(self, class_name, name_pattern, match):
        names = sorted(
            name for (cls, name) in self.devices if cls == class_name and fnmatch.fnmatch(name, name_pattern)
        )
        return [
            name for name in names if all(self._matches(class_name, name, k, v) for k, v in match.items())
        ]

    def _matches(self, class_name, name, attribute, pattern):
        value = self.devices[(class_name, name)].get(attribute)
        if value is None:
            return False
        value = self._peek(value)
        if isinstance(pattern, list):
            return any(value.find(p) >= 0 for p in pattern)
        return value.find(pattern) >= 0

    @staticmethod
    def _peek(value):
        return value[0] if isinstance(value, list) else value

    def _device(self, class_name, name, attribute):
        device = self.devices.get((class_name, name))
        if device is None or attribute not in device:
            raise OSError(
                errno.ENOENT, "No such file or directory", f"/sys/class/{class_name}/{name}/{attribute}"
            )
        return device

    def read(self, class_name, name, attribute):
        device = self._device(class_name, name, attribute)
        self.log.append(["read", name, attribute])
        value = device[attribute]
        if isinstance(value, list):
            value = value.pop(0) if len(value) > 1 else value[0]
        return value + "\n"

    def write(self, class_name, name, attribute, value):
        if not isinstance(value, str):  # a backend takes bytes too (set_attr_raw), as latin-1
            value = bytes(value).decode("latin-1")
        device = self._device(class_name, name, attribute)
        self.log.append(["write", name, attribute, value])
        if attribute == "speed_sp" and abs(int(value)) > int(self._peek(device["max_speed"])):
            raise OSError(errno.EINVAL, "Invalid argument")
        if attribute in ("command", "direct", "set_device"):
            device[attribute] = value
        elif not isinstance(device[attribute], list):
            device[attribute] = value

    def poll(self, class_name, name, attribute, timeout_ms):
        self.log.append(["poll", name, attribute, timeout_ms])
        self.clock += timeout_ms / 1000

    def call(self, feature, *args):
        self.calls.append([feature, *args])
        if feature == "buttons":
            return list(self.buttons)
        if feature == "sound" and args[0] == "set_volume":
            self.volume = args[1]["pct"]
        if feature == "sound" and args[0] == "get_volume":
            return self.volume
        return None

    # -- reading the log --------------------------------------------------
    def writes(self, name=None):
        """The (device, attribute, value) of every write, optionally of one device."""
        return [
            tuple(entry[1:])
            for entry in self.log
            if entry[0] == "write" and (name is None or entry[1] == name)
        ]

    def reads(self, name=None):
        return [
            tuple(entry[1:])
            for entry in self.log
            if entry[0] == "read" and (name is None or entry[1] == name)
        ]

    def clear_log(self):
        self.log.clear()
