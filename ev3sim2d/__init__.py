"""ev3sim2d: a 2D top-down simulator for LEGO Mindstorms EV3 robots.

The Python API: `simulate(program, world)` runs programs and returns a `SimulationResult`; worlds
are loaded with `load_maze` or built with `World.from_text`.  Heavier modules load on first use.
"""

from __future__ import annotations

__all__ = ["SimulationResult", "Table", "World", "load_maze", "simulate"]

_WHERE = {
    "simulate": "ev3sim2d.simulate",
    "SimulationResult": "ev3sim2d.simulate",
    "Table": "ev3sim2d.results.table",
    "World": "ev3sim2d.world.world",
    "load_maze": "ev3sim2d.world.maze_file",
}


def __getattr__(name: str):
    """The public names, imported when first asked for (the brick and the CLI import this package too)."""
    if name not in _WHERE:
        raise AttributeError(f"module 'ev3sim2d' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(_WHERE[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted([*globals(), *__all__])
