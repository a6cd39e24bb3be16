"""Small worlds and made-up traces for testing checks without running a program."""

from ev3sim2d.grading.run_record import RunRecord
from ev3sim2d.results.trace import Trace
from ev3sim2d.world.maze_file import parse_maze

MOTORS = [["outA", "medium"], ["outB", "large"], ["outC", "large"]]


def room(
    extra: str = "",
    legend: str = "",
    inner: list[str] | None = None,
    start="{x_cm: 30, y_cm: 30, heading_deg: 0}",
):
    """A 10 x 8 room of 10 cm cells (floor x 10..90, y 10..70); `inner` replaces its six inner rows."""
    rows = ["#" * 10] + (inner or ["#" + "." * 8 + "#"] * 6) + ["#" * 10]
    grid = "\n".join("  " + r for r in rows)
    text = f"title: test room\ncell_cm: 10\n{legend}grid: |\n{grid}\nstart: {start}\n{extra}"
    return parse_maze(text, "<test room>")


def trace_of(
    world, poses, touching=None, speeds=None, dt=0.01, status="finished", error=None, touching_robot=None
):
    """A trace whose robot goes through `poses` (x, y, heading), the first being its start, one per tick;
    `touching` and `touching_robot` say per pose whether it touches a wall, another robot."""
    x0, y0, h0 = poses[0]
    robots = [
        {
            "name": "robot",
            "start": {"x_cm": x0, "y_cm": y0, "heading_deg": h0},
            "motors": MOTORS,
            "sensors": [],
            "wheels": ["outB", "outC"],
        }
    ]
    trace = Trace(dt, robots, {"name": world.name, "title": world.title, "text": world.text}, 0)
    for i, (x, y, h) in enumerate(poses[1:], start=1):
        touch = 1.0 if touching and touching[i] else 0.0
        bump = 1.0 if touching_robot and touching_robot[i] else 0.0
        left, right = speeds[i] if speeds else (0.0, 0.0)
        trace.add_tick(round(i * dt, 6), [x, y, h, touch, bump, 0, 0, 0, 0, left, 0, 0, right, 0])
    trace.result = {"status": status, "sim_time_s": round((len(poses) - 1) * dt, 6), "error": error}
    return trace


def record(world, poses, end_driving=False, **options):
    trace = trace_of(world, poses, **options)
    trace.end_motors = [{"driving": end_driving, "states": {}}]
    return RunRecord(trace, world, 60.0)


def line(start, end, steps, heading=None):
    """Poses along a straight line from start to end (x, y), `steps` ticks."""
    (x0, y0), (x1, y1) = start, end
    import math

    h = heading if heading is not None else math.degrees(math.atan2(y1 - y0, x1 - x0))
    return [(x0 + (x1 - x0) * i / steps, y0 + (y1 - y0) * i / steps, h) for i in range(steps + 1)]
