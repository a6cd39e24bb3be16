"""Values of a run against time as a chart: sensor readings, motor speeds, the pose (matplotlib).

matplotlib is an optional extra (`pip install 'ev3sim2d[plot]'`), imported only when a chart is
drawn.  Each value gets a panel of its own unit, one above the other on a shared time axis:
sensors by port (`in3`), motors as `outB.speed` (deg/s) or `outB.position` (deg), and `x_cm`,
`y_cm`, `heading_deg`, `touching`.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ..series import RobotSeries, robot_series
from ..trace import Trace

INSTALL_HINT = "plotting needs matplotlib: pip install 'ev3sim2d[plot]' (or pip install matplotlib)"


def default_values(series: RobotSeries) -> list[str]:
    """What a chart shows when not told: every sensor whose reading changed, and the motors that turned."""
    sensors = [port for port, values in series.sensors.items() if np.nanmax(values) != np.nanmin(values)]
    speeds = [name for name in series.motors if name.endswith(".speed") and any(series.motors[name])]
    return sensors + speeds or ["x_cm", "y_cm"]


def plot(trace: Trace, values: Sequence[str] | None = None, robot: int = 0, width_in: float = 8.0):
    """A matplotlib Figure of `values` (timeline names) of robot `robot` against time.

    Values sharing a unit (all motor speeds, say) share a panel.  Raises ImportError with the install
    command when matplotlib is missing, KeyError naming the known timelines for an unknown name.
    """
    try:
        from matplotlib.figure import Figure
    except ImportError:
        raise ImportError(INSTALL_HINT) from None
    series = robot_series(trace, robot)
    names = list(values) if values else default_values(series)
    columns = [(name, series.column(name)) for name in names]
    panels: dict[str, list[str]] = {}
    for name in names:
        panels.setdefault(_unit(name, series), []).append(name)
    figure = Figure(figsize=(width_in, 1.9 * len(panels) + 0.6), layout="constrained")
    axes = figure.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    data = dict(columns)
    for ax, (unit, members) in zip(axes, panels.items(), strict=True):
        for name in members:
            label = f"{name} ({series.sensor_kinds[name]})" if name in series.sensor_kinds else name
            ax.step(series.times, data[name], where="post", label=label, linewidth=1.2)
        ax.set_ylabel(unit)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize="small")
    axes[-1].set_xlabel("time (s)")
    figure.suptitle(
        f"{series.name} in {trace.world.get('title') or trace.world.get('name')}", fontsize="medium"
    )
    return figure


def plot_png(
    trace: Trace, values: Sequence[str] | None = None, robot: int = 0, path: str | Path | None = None
) -> bytes:
    """The chart of `plot` as PNG bytes, also written to `path` when given."""
    buffer = io.BytesIO()
    plot(trace, values, robot).savefig(buffer, format="png", dpi=100)
    data = buffer.getvalue()
    if path is not None:
        Path(path).write_bytes(data)
    return data


def _unit(name: str, series: RobotSeries) -> str:
    if name in series.sensor_kinds:
        return series.sensor_kinds[name]
    if name.endswith(".speed"):
        return "speed (deg/s)"
    if name.endswith(".position"):
        return "position (deg)"
    return {"x_cm": "cm", "y_cm": "cm", "heading_deg": "degrees", "touching": "touching"}.get(name, name)
