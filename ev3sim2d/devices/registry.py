"""Device kinds by the names robot files use: a new kind of device is one new file and one line here.

A sensor class says all the rest itself (sensor.py, LegoSensor: KIND, DRIVER, MODES, FACINGS,
OPTIONS, how the video shows it), so robot files, the video and a program's ev3dev2 learn it from
the class.  A kind from outside ev3sim2d (a package of one's own) comes in one of two ways
(docs/devices.md): an entry point in the group `ev3sim2d.devices` (name: the kind, value:
`module:Class`), which every command finds once the package is installed, or `register(Class)`
in the Python that runs the simulation.
"""

from __future__ import annotations

import inspect
from importlib import metadata

from .color import ColorSensor
from .gyro import GyroSensor
from .infrared import InfraredSensor
from .motor import KINDS as MOTOR_KINDS
from .nxt_light import NxtLightSensor
from .nxt_sound import NxtSoundSensor
from .sensor import LegoSensor
from .touch import TouchSensor
from .ultrasonic import UltrasonicSensor

BUILT_IN = (
    TouchSensor,
    GyroSensor,
    ColorSensor,
    UltrasonicSensor,
    InfraredSensor,
    NxtLightSensor,
    NxtSoundSensor,
)
ENTRY_POINT_GROUP = "ev3sim2d.devices"
FACINGS = ("forward", "down")
MOTORS = tuple(MOTOR_KINDS)


class DeviceKindError(ValueError):
    """A device class, or a plug-in naming one, that ev3sim2d cannot use: the message says why and the fix."""


class _SensorKinds(dict):
    """Kind -> sensor class; a kind not registered yet is looked for among the installed plug-ins."""

    def __missing__(self, kind: str) -> type[LegoSensor]:
        found = _from_entry_point(kind)
        if found is None:
            raise KeyError(
                f"no kind of sensor is called {kind!r}; the kinds are {', '.join(sensor_kinds())} "
                f"(a kind of one's own: docs/devices.md)"
            )
        return found


SENSORS: dict[str, type[LegoSensor]] = _SensorKinds()
"""Every kind of sensor registered so far (the plug-ins are added when first asked for)."""


def register(cls: type[LegoSensor]) -> type[LegoSensor]:
    """Make `cls` the sensor of kind `cls.KIND` in robot files; returns it (so it serves as a decorator).

    Checks what robot files, the video and a program rely on, and says what to fix in the class's file.
    Registering the same class again does nothing; another class under a kind already taken is refused.
    """
    where = _where(cls)
    if not (isinstance(cls, type) and issubclass(cls, LegoSensor)):
        raise DeviceKindError(
            f"{where}: {cls!r} is not a sensor class; "
            "subclass ev3sim2d.devices.sensor.LegoSensor (docs/devices.md)"
        )
    name = cls.__name__
    kind = cls.__dict__.get("KIND", "")
    if not isinstance(kind, str) or not kind.strip() or kind != kind.strip().lower():
        inherited = f" (it inherits {cls.KIND!r})" if cls.KIND else ""
        raise DeviceKindError(
            f"{where}: {name} needs its own KIND, the lower-case name robot files give it{inherited}; "
            'add e.g. `KIND = "light-gate"` to the class'
        )
    if not cls.DRIVER:
        raise DeviceKindError(
            f"{where}: {name} has no DRIVER, the driver name a program finds it by; "
            f'add e.g. `DRIVER = "my-{kind}"` to the class'
        )
    if not cls.MODES:
        raise DeviceKindError(
            f'{where}: {name} has no MODES; add e.g. `MODES = {{"VALUE": Mode(1)}}` '
            "(from ev3sim2d.devices.sensor import Mode)"
        )
    wrong = [f for f in cls.FACINGS if f not in FACINGS]
    if not cls.FACINGS or wrong:
        raise DeviceKindError(
            f"{where}: {name}.FACINGS must list some of {', '.join(FACINGS)}, got {cls.FACINGS!r}"
        )
    known = SENSORS.get(kind)
    if known is not None and known is not cls:
        raise DeviceKindError(
            f"{where}: {name} wants kind {kind!r}, which is {known.__name__}'s ({_where(known)}); "
            "give it another KIND"
        )
    SENSORS[kind] = cls
    return cls


def sensor_class(kind: str) -> type[LegoSensor] | None:
    """The sensor class of `kind`, registered or from an installed plug-in; None if there is none."""
    found = SENSORS.get(kind)
    return found if found is not None else _from_entry_point(kind)


def sensor_kinds() -> tuple[str, ...]:
    """The names robot files may give a sensor's kind: the registered ones, then the installed plug-ins'."""
    names = list(SENSORS)
    names += sorted({ep.name for ep in _entry_points()} - set(names))
    return tuple(names)


def _entry_points() -> list[metadata.EntryPoint]:
    return list(metadata.entry_points(group=ENTRY_POINT_GROUP))


def _from_entry_point(kind: str) -> type[LegoSensor] | None:
    """Load and register the plug-in sensor of `kind`, if a package installed one."""
    for ep in _entry_points():
        if ep.name != kind:
            continue
        source = f"the {ENTRY_POINT_GROUP} entry point {ep.name} = {ep.value}" + (
            f" (package {ep.dist.name})" if getattr(ep, "dist", None) is not None else ""
        )
        try:
            cls = ep.load()
        except Exception as error:  # the plug-in's own bug or a wrong name: say which plug-in
            raise DeviceKindError(f"{source} does not load: {type(error).__name__}: {error}") from error
        if getattr(cls, "KIND", None) != kind:
            raise DeviceKindError(
                f"{source} names a class whose KIND is {getattr(cls, 'KIND', None)!r}; "
                f"the entry point's name and the class's KIND must be the same"
            )
        return register(cls)
    return None


def _where(cls: object) -> str:
    """The file a class is written in, for messages (its module's name if that is unknown)."""
    try:
        return inspect.getsourcefile(cls) or cls.__module__  # type: ignore[arg-type]
    except (TypeError, OSError):
        return getattr(cls, "__module__", "?")


for _sensor in BUILT_IN:
    register(_sensor)
