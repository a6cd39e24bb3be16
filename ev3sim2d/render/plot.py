"""Values of a run against time as a chart: sensor readings, motor speeds, the pose (matplotlib).

matplotlib is an optional extra (`pip install 'ev3sim2d[plot]'`), imported only when a chart is
drawn.  Each value gets a panel of its own unit, one above the other on a shared time axis:
sensors by port (`in3`, in the unit of the mode the program read: reflected light in %, distance in
cm), motors as `outB.speed` (deg/s) or `outB.position` (deg), and `x_cm`, `y_cm`, `heading_deg`,
`touching`.  `ev3sim2d plot` and `run --plot` draw it from the command line.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..devices.registry import sensor_class
from ..results.output_files import write_file
from ..results.series import RobotSeries, held_readings, robot_series
from ..results.trace import Trace

INSTALL_HINT = "plotting needs matplotlib: pip install 'ev3sim2d[plot]' (or pip install matplotlib)"
DPI = 100  # pixels per inch of the PNG: a size in pixels is the figure's inches times this
DEFAULT_WIDTH_IN = 8.0

# what a student calls a sensor mode's first value, with its unit (others: the mode and the driver's unit)
MODE_LABELS = {
    "COL-REFLECT": "reflected light (%)",
    "COL-AMBIENT": "ambient light (%)",
    "COL-COLOR": "colour (0 none, 1 black … 6 white, 7 brown)",
    "REFLECT": "reflected light (%)",
    "AMBIENT": "ambient light (%)",
    "US-DIST-CM": "distance (cm)",
    "US-SI-CM": "distance (cm)",
    "US-DC-CM": "distance (cm)",
    "US-DIST-IN": "distance (in)",
    "US-SI-IN": "distance (in)",
    "US-DC-IN": "distance (in)",
    "US-LISTEN": "another ultrasonic heard (0/1)",
    "GYRO-ANG": "angle (°)",
    "TILT-ANG": "tilt angle (°)",
    "GYRO-RATE": "turn rate (°/s)",
    "TILT-RATE": "tilt rate (°/s)",
    "GYRO-G&A": "angle (°)",
    "TOUCH": "pressed (0/1)",
    "IR-PROX": "proximity (%)",
    "DB": "sound (%)",
    "DBA": "sound (%)",
}
POSE_LABELS = {
    "x_cm": ("position (cm)", "the robot's x position (cm)"),
    "y_cm": ("position (cm)", "the robot's y position (cm)"),
    "heading_deg": ("heading (°)", "the robot's heading (°, counter-clockwise from the x axis)"),
    "touching": ("touching a wall (0/1)", "1 while the robot's body touches a wall"),
}


@dataclass
class Timeline:
    """One value of a robot against time, in the unit a student reads it in."""

    name: str  # as `values` names it: 'in3', 'outB.speed', 'x_cm'
    unit: str  # the panel's label: 'reflected light (%)'
    description: str  # a line for `ev3sim2d plot --list`
    values: np.ndarray


def timelines(trace: Trace, robot: int = 0) -> dict[str, Timeline]:
    """Every value of robot `robot` a chart can show, by name: its sensors, its motors, its pose."""
    series = robot_series(trace, robot)
    found: dict[str, Timeline] = {}
    for port, kind in series.sensor_kinds.items():
        unit, values = _sensor_reading(trace, robot, port, kind, series.times)
        found[port] = Timeline(port, unit, f"{kind} sensor: {unit}", values)
    kinds = dict(trace.robots[robot]["motors"])
    for name, values in series.motors.items():
        port, what = name.split(".")
        unit = "speed (°/s)" if what == "speed" else "position (°)"
        found[name] = Timeline(name, unit, f"{kinds.get(port, '')} motor {port}: {unit}".strip(), values)
    columns = series.columns()
    for name, (unit, description) in POSE_LABELS.items():
        found[name] = Timeline(name, unit, description, columns[name])
    return found


def default_values(series: RobotSeries) -> list[str]:
    """What a chart shows when not told: every sensor whose reading changed, and the motors that turned."""
    sensors = [
        port
        for port, values in series.sensors.items()
        if not np.isnan(values).all() and np.nanmax(values) != np.nanmin(values)
    ]
    speeds = [name for name in series.motors if name.endswith(".speed") and any(series.motors[name])]
    return sensors + speeds or ["x_cm", "y_cm"]


def plot(trace: Trace, values: Sequence[str] | None = None, robot: int = 0, width_in: float = 8.0):
    """A matplotlib Figure of `values` (timeline names) of robot `robot` against time.

    Values sharing a unit (all motor speeds, say) share a panel.  Raises ImportError with the install
    command when matplotlib is missing, KeyError naming the known timelines for an unknown name.
    """
    return chart(trace, values, robot, size_in=(width_in, None))


def chart(
    trace: Trace,
    values: Sequence[str] | None = None,
    robot: int = 0,
    size_in: tuple[float, float | None] = (DEFAULT_WIDTH_IN, None),
    start_s: float | None = None,
    end_s: float | None = None,
):
    """`plot` with the whole size (height None: by the number of panels) and a time window to show."""
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise ImportError(INSTALL_HINT) from None
    series = robot_series(trace, robot)
    names = list(values) if values else default_values(series)
    for name in names:
        series.column(name)  # KeyError naming the known ones
    known = timelines(trace, robot)
    shown = np.ones(len(series.times), dtype=bool)
    if start_s is not None:
        shown &= series.times >= start_s - 1e-9
    if end_s is not None:
        shown &= series.times <= end_s + 1e-9
    panels: dict[str, list[Timeline]] = {}
    for name in names:
        timeline = known.get(name) or Timeline(name, name, name, series.column(name))
        panels.setdefault(timeline.unit, []).append(timeline)
    width_in, height_in = size_in
    figure = Figure(figsize=(width_in, height_in or 1.9 * len(panels) + 0.6), dpi=DPI, layout="constrained")
    axes = figure.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (unit, members) in zip(axes, panels.items(), strict=True):
        for timeline in members:
            kind = series.sensor_kinds.get(timeline.name)
            label = f"{timeline.name} ({kind})" if kind else timeline.name
            ax.step(series.times[shown], timeline.values[shown], where="post", label=label, linewidth=1.2)
        ax.set_ylabel(unit)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize="small")
    axes[-1].set_xlabel("time (s)")
    figure.suptitle(
        f"{series.name} in {trace.world.get('title') or trace.world.get('name')}", fontsize="medium"
    )
    return figure


def plot_png(
    trace: Trace,
    values: Sequence[str] | None = None,
    robot: int = 0,
    path: str | Path | None = None,
    size_px: tuple[int, int] | None = None,
    start_s: float | None = None,
    end_s: float | None = None,
) -> bytes:
    """The chart of `plot` as PNG bytes (`size_px` wide and high, else 800 wide and high enough for
    its panels), also written to `path` when given."""
    size_in = (size_px[0] / DPI, size_px[1] / DPI) if size_px else (DEFAULT_WIDTH_IN, None)
    figure = chart(trace, values, robot, size_in, start_s, end_s)
    buffer = io.BytesIO()
    figure.savefig(buffer, format="png", dpi=DPI)
    data = buffer.getvalue()
    if path is not None:
        write_file(path, data)
    return data


def _sensor_reading(trace: Trace, robot: int, port: str, kind: str, times: np.ndarray):
    """A sensor's unit label and its first value at each time in that unit (the driver gives mm as
    tenths of a cm: value0 / 10**decimals, as ev3dev2's distance_centimeters does)."""
    cls = sensor_class(kind)
    modes = cls.MODES if cls is not None else {}
    seen = list(
        dict.fromkeys(mode for _t, r, p, mode, _v in trace.sensor_samples if r == robot and p == port)
    )

    def in_unit(mode: str, values: list) -> float:
        return float(values[0]) / 10 ** (modes[mode].decimals if mode in modes else 0)

    labels = [MODE_LABELS.get(mode) or _driver_label(mode, modes) for mode in seen]
    unit = " / ".join(dict.fromkeys(labels)) or f"{kind} (never read)"
    return unit, held_readings(trace, robot, port, times, in_unit)


def _driver_label(mode: str, modes: dict) -> str:
    units = modes[mode].units if mode in modes else ""
    return f"{mode} ({units})" if units else mode
