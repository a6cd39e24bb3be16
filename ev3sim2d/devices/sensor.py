"""EV3 sensors as the ev3dev lego-sensor driver shows them: modes, value0..N, decimals, units.

A sensor measures lazily: the first read in a tick computes the values of the
current mode from the world (and adds the sensor's noise, if any); later reads
in the same tick return the same numbers, as a real sensor's sample does.
Each kind of sensor is one subclass that lists its modes and measures them.
"""

from __future__ import annotations

import errno
import math
import os
import struct
from dataclasses import dataclass
from typing import Protocol

from .device import Device, invalid


@dataclass(frozen=True)
class Mode:
    """One mode of a sensor, as the driver reports it."""

    num_values: int
    decimals: int = 0
    units: str = ""
    data_format: str = "s8"
    low: float = -128
    high: float = 127
    noisy: bool = True  # False for values that name something (a colour, a button): noise would garble them
    # the driver's raw_min, raw_max, si_min, si_max when bin_data holds unscaled readings that value<N> scales
    # (the NXT analog sensors: millivolts); None when bin_data holds the values themselves (the EV3 sensors)
    raw: tuple[int, int, int, int] | None = None


class Surroundings(Protocol):
    """What a sensor may ask of the robot it sits on (the robot implements this)."""

    tick: int
    rng: object

    def sensor_pose(self, mount: tuple[float, float, float]) -> tuple[float, float, float]: ...
    def ray(self, x: float, y: float, direction: float, max_cm: float) -> float | None: ...
    def cone(self, x: float, y: float, direction: float, half_rad: float, max_cm: float) -> float | None: ...
    def near(self, x: float, y: float, reach_cm: float) -> bool: ...


SAMPLES_PER_TICK = 6
"""Measurements of one sensor the trace records per tick.  An honest program changes a sensor's mode (a
3 ms write) at most four times in a 10 ms tick, so records at most five; a brick that sends writes
without spending time gets its later measurements served but only the tick's last one recorded in the
last place, so that the trace grows with virtual time only."""

_FORMATS = {"u8": "B", "s8": "b", "u16": "H", "s16": "h", "s16_be": ">h", "s32": "i", "float": "f"}


class LegoSensor(Device):
    """Base of the sensors: mode handling, value attributes, per-tick sampling and noise."""

    sysfs_class = "lego-sensor"
    name_prefix = "sensor"
    # What a kind of sensor says about itself, so that it is one file and one line in registry.py
    # (docs/devices.md): robot files, the video and a program's ev3dev2 all learn it from here.
    KIND = ""  # its name in robot files (`kind: ultrasonic`)
    DRIVER = ""  # its driver's name, as a program finds it (`Sensor(INPUT_1, driver_name=...)`)
    MODES: dict[str, Mode] = {}  # the first is the mode it starts in
    FACINGS: tuple[str, ...] = (
        "down",
        "forward",
    )  # the ways `measure` models it facing; the first is the default
    FACING_HINTS: dict[str, str] = {}  # a facing it does not model -> why not, and what to write instead
    OPTIONS: dict[str, tuple[float, str, str]] = {}  # extra robot-file keys: name -> (default, unit, meaning)
    # how the video shows it (render/): its name in the panel (default: KIND); its housing on the robot:
    # "box", "bumper" or "eyes" (the ultrasonic and infrared sensors' two); whether it shows the floor
    # spot it sees when it faces down; and `beam_cm`, the distance its beam reaches by a reading
    LABEL = ""
    HOUSING = "box"
    FLOOR_SPOT = False
    BEAM_APPROXIMATE = False  # the beam's distance is an estimate ("≈12 cm"), not a measurement ("12.3 cm")

    @classmethod
    def beam_cm(cls, mode: str, values: list[int], max_cm: float) -> float | None:
        """How far the sensor's beam reaches (cm) by a reading in `mode`; None: it has no beam to draw."""
        return None

    def __init__(self, address: str, spec, surroundings: Surroundings) -> None:
        super().__init__(address, self.DRIVER)
        self.spec = spec
        self.around = surroundings
        self._cone = getattr(surroundings, "cone", None)  # (the robot's; see nearest_in_cone)
        self.noise = float(getattr(spec, "noise", 0.0) or 0.0)
        # where it sits: radius (cm), direction from the robot centre and aim (radians from the heading)
        self.mount = (
            spec.radius_cm,
            math.radians(spec.angle_deg),
            math.radians(getattr(spec, "aim_deg", 0.0)),
        )
        self.mode = next(iter(self.MODES))
        self._sample_tick = -1
        self._sample_mode = ""
        self._sample: tuple[int, ...] = ()
        self.samples: list[tuple[int, str, tuple[int, ...]]] = []  # (tick, mode, values) of every measurement
        self._recorded = (-1, 0)  # the tick of the last sample recorded, and how many were in that tick
        # per mode, how a measurement becomes the driver's value: 10 ** decimals, its bounds, whether noisy
        self._scaling = {name: (10**m.decimals, m.low, m.high, m.noisy) for name, m in self.MODES.items()}
        r, w = self.readers, self.writers
        r.update(
            mode=lambda: self.mode,
            modes=lambda: " ".join(self.MODES),
            num_values=lambda: str(self.MODES[self.mode].num_values),
            decimals=lambda: str(self.MODES[self.mode].decimals),
            units=lambda: self.MODES[self.mode].units,
            bin_data_format=lambda: self.MODES[self.mode].data_format,
            bin_data=self._bin_data,
            commands=lambda: "",
        )
        for n in range(8):
            r[f"value{n}"] = lambda n=n: self._value(n)
        w.update(mode=self._set_mode, command=self._set_command)
        self.write_rules["mode"] = ["choice", list(self.MODES)]
        self.constants |= {"modes", "commands"}
        self.settings |= {"mode", "num_values", "decimals", "units", "bin_data_format"}

    # ------------------------------------------------------------ attributes
    def _set_mode(self, value: str) -> None:
        mode = value.strip()
        if mode not in self.MODES:
            raise invalid(value)
        if mode != self.mode:
            self.mode = mode
            self.mode_changed()
        self.mode_selected()

    def _set_command(self, value: str) -> None:
        raise invalid(value)  # the EV3 sensors take no commands

    def mode_changed(self) -> None:
        """Hook for sensors whose state changes with the mode (the gyro resets)."""

    def mode_selected(self) -> None:
        """Hook called on every write of `mode`, the same mode or another: the driver sends the sensor its
        SELECT message each time (the ultrasonic sensor's single-measurement modes measure then)."""

    def values(self) -> tuple[int, ...]:
        """The current mode's values for this tick, as the driver gives them (scaled integers)."""
        tick, mode = self.around.tick, self.mode
        if self._sample_tick == tick and self._sample_mode == mode:
            return self._sample
        scale, low, high, noisy = self._scaling[mode]
        noise = self.noise if noisy else 0.0
        sample = []
        for v in self.measure(mode):
            if noise:
                v += self.around.rng.normal(0.0, noise)
            v = round(v * scale)
            sample.append(int(low if v < low else high if v > high else v))
        self._sample = sample = tuple(sample)
        self._sample_tick, self._sample_mode = tick, mode
        # recorded: at most SAMPLES_PER_TICK a tick, then the tick's last replaces the one before
        recorded_tick, count = self._recorded
        if recorded_tick != tick:
            count = 0
        if count < SAMPLES_PER_TICK:
            self.samples.append((tick, mode, sample))
            count += 1
        else:
            self.samples[-1] = (tick, mode, sample)
        self._recorded = (tick, count)
        return sample

    def _value(self, n: int) -> str:
        values = self.values()
        if n < len(values):
            return str(values[n])
        # lego_sensor_class.c value_show: index >= num_values -> -ENXIO ("No such device or address")
        # (a real brick's read of the file raises OSError: [Errno 6] No such device or address)
        raise OSError(errno.ENXIO, os.strerror(errno.ENXIO))

    def _bin_data(self) -> str:
        mode = self.MODES[self.mode]
        fmt = _FORMATS[mode.data_format]
        values = self.values()
        if mode.raw is not None:  # unscaled readings: value = (raw - raw_min) * si span / raw span + si_min
            raw_min, raw_max, si_min, si_max = mode.raw
            values = [raw_min + round((v - si_min) * (raw_max - raw_min) / (si_max - si_min)) for v in values]
        data = b"".join(struct.pack(fmt if fmt.startswith(">") else "<" + fmt, v) for v in values)
        return data.decode("latin-1")

    # ------------------------------------------------------------- measuring
    def measure(self, mode: str) -> tuple[float, ...]:
        """The values of `mode` now, in the mode's units (before scaling by decimals)."""
        raise NotImplementedError

    def nearest_in_cone(self, cone_deg: float, max_cm: float) -> float:
        """Distance to the nearest point of a wall or robot anywhere inside the cone (`cone_deg` wide, around
        the way the sensor faces); max_cm if none is nearer."""
        x, y, facing = self.position()
        cone = self._cone
        if cone is None:  # surroundings that only cast rays (a stand-in): the cone's axis and edges
            half = math.radians(cone_deg) / 2.0
            hits = [self.around.ray(x, y, facing + offset, max_cm) for offset in (0.0, -half, half)]
            return min([max_cm, *(hit for hit in hits if hit is not None)])
        hit = cone(x, y, facing, cone_deg * (math.pi / 360.0), max_cm)  # (the half-angle)
        return max_cm if hit is None else hit

    def position(self) -> tuple[float, float, float]:
        """Where the sensor is: x, y (cm) and the direction it faces (radians)."""
        return self.around.sensor_pose(self.mount)
