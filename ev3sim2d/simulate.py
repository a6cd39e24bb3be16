"""The Python API: run ev3dev2 programs in a world from Python or a notebook, and look at what happened.

    from ev3sim2d import simulate
    result = simulate("examples/line_follower.py", world="line", time_s=10)
    result.poses[-1]             # x_cm, y_cm, heading_deg at the end
    result.sensors["in3"]        # the colour sensor's reading at every tick
    result.png("end.png"); result.plot(["in3", "outB.speed", "outC.speed"])

A program is a file or its source as a string; a world is a shipped world's name, a world file or a
World built in Python (`World.from_text`).  Programs run as with `ev3sim2d run`: each in a sandboxed
brick process of its own, so a result is the same, fingerprint for fingerprint.
"""

from __future__ import annotations

import base64
import html
import os
import tempfile
import textwrap
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from .results.output_files import write_file
from .results.series import RobotSeries, robot_series
from .results.table import Table
from .results.trace import OutputLine, Trace
from .simulator.program import ProgramError, source_with_caret
from .simulator.run import RunResult, run_programs, start_failure
from .world.maze_file import find_maze, load_maze
from .world.robot_spec import RobotSpec, find_robot, load_robot, shipped_robot_names
from .world.world import World

INLINE_VIDEO_UP_TO_S = 30.0
"""Runs up to this long show as a video in a notebook; longer ones as the picture of their end."""
INLINE_VIDEO_SIZE = (640, 360)
INLINE_VIDEO_FPS = 15.0
INLINE_MAX_BYTES = 3_000_000
"""A video bigger than this is not put into a notebook (the picture of the end is, instead)."""


class SimulationResult:
    """What happened in a run: how it ended, each robot's timelines, what the programs printed.

    `times`, `poses`, `sensors` and `motors` are the first robot's (`robots[i]` has each robot's);
    they all have one entry per time in `times` (the start, then every tick).
    """

    def __init__(self, run: RunResult) -> None:
        self.run = run
        self.trace: Trace = run.trace
        self.robots: list[RobotSeries] = [robot_series(run.trace, i) for i in range(len(run.trace.robots))]

    # -- how it ended --------------------------------------------------------------------------
    @property
    def status(self) -> str:
        """finished, error, time_limit, hung, interrupted or crashed."""
        return self.run.status

    @property
    def reason(self) -> str:
        """How the run ended, in one line."""
        return self.run.reason

    @property
    def error(self) -> dict | None:
        """The program's error (type, message, file, line, t_s, traceback), if it raised one."""
        return self.run.error

    @property
    def sim_time_s(self) -> float:
        """Simulated seconds the run lasted."""
        return self.run.sim_time_s

    @property
    def fingerprint(self) -> str:
        """A hash of everything recorded: two runs with the same fingerprint did the same."""
        return self.trace.fingerprint()

    # -- timelines -----------------------------------------------------------------------------
    @property
    def times(self) -> np.ndarray:
        """Seconds: 0 (the start), then the end of every tick."""
        return self.robots[0].times

    @property
    def poses(self) -> np.ndarray:
        """The first robot's (x_cm, y_cm, heading_deg) at each time; heading 0 = +x, counter-clockwise."""
        return self.robots[0].poses

    @property
    def sensors(self) -> dict[str, np.ndarray]:
        """The first robot's sensors by port ('in3'): the first value of each reading as the driver gives it
        (before python-ev3dev2 scales it: the ultrasonic sensor in mm), held until the next reading."""
        return self.robots[0].sensors

    @property
    def motors(self) -> dict[str, np.ndarray]:
        """The first robot's motors: 'outB.speed' in deg/s and 'outB.position' in degrees."""
        return self.robots[0].motors

    @property
    def output(self) -> list[OutputLine]:
        """Every line the programs printed, with its time (t_s), robot, stream and text."""
        return list(self.trace.output)

    @property
    def printed(self) -> str:
        """What the programs printed, as one text."""
        return "".join(line.text + "\n" for line in self.trace.output)

    def table(self, every_s: float | None = None, robot: int = 0) -> Table:
        """The timelines of robot `robot` as a table (t_s, x_cm, y_cm, heading_deg, touching, sensors,
        motors), every tick or every `every_s` seconds."""
        series = self.robots[robot]
        columns = series.columns()
        if every_s:
            wanted = np.arange(0.0, series.times[-1] + 1e-9, every_s)
            rows = np.searchsorted(series.times, wanted + 1e-9, side="right") - 1
            columns = {name: values[rows] for name, values in columns.items()}
        return Table(columns)

    # -- pictures ------------------------------------------------------------------------------
    def png(self, path: str | Path | None = None, size: tuple[int, int] = (1280, 720)) -> bytes:
        """The picture of the end of the run (as `run --png`), as PNG bytes; also written to `path`."""
        import cv2

        from .render.frame import draw_final_frame

        ok, encoded = cv2.imencode(".png", draw_final_frame(self.trace, size))
        if not ok:
            raise RuntimeError("could not encode the picture as PNG")
        data = encoded.tobytes()
        if path is not None:
            write_file(path, data)
        return data

    def video(
        self,
        path: str | Path | None = None,
        fps: float = 30.0,
        speed: float = 1.0,
        size: tuple[int, int] = (1280, 720),
        audio: bool = True,
    ) -> bytes:
        """The video of the run (H.264 MP4, as `run --video`), as bytes; also written to `path`."""
        from .render.video import VideoOptions, write_video

        options = VideoOptions(fps=fps, speed=speed, size=size, audio=audio)
        with tempfile.TemporaryDirectory(prefix="ev3sim2d-video-") as folder:
            target = Path(path) if path is not None else Path(folder) / "run.mp4"
            write_video(self.trace, target, options, progress=False)
            return target.read_bytes()

    def plot(self, values: Sequence[str] | None = None, path: str | Path | None = None, robot: int = 0):
        """A matplotlib Figure of timelines against time (default: the sensors whose reading changed, and the motors that turned);
        with `path`, also written there as PNG.  Needs matplotlib: pip install 'ev3sim2d[plot]'."""
        from .render.plot import plot

        figure = plot(self.trace, values, robot)
        if path is not None:
            figure.savefig(path, dpi=100)
        return figure

    # -- in a notebook -------------------------------------------------------------------------
    def summary(self) -> dict[str, str]:
        """A few facts for a glance: how it ended, how long, where each robot got to, what was printed."""
        facts = {"status": self.status, "reason": self.reason, "simulated": f"{self.sim_time_s:.2f} s"}
        for series in self.robots:
            x, y, heading = series.poses[-1]
            steps = np.diff(series.poses[:, :2], axis=0)
            travelled = float(np.hypot(steps[:, 0], steps[:, 1]).sum())
            facts[series.name] = (
                f"ends at x {x:.1f} cm, y {y:.1f} cm, heading {heading:.0f}°, after {travelled:.1f} cm"
            )
        facts["printed"] = f"{len(self.trace.output)} lines"
        facts["fingerprint"] = self.fingerprint
        return facts

    def _repr_html_(self) -> str:
        media = None
        if self.sim_time_s <= INLINE_VIDEO_UP_TO_S:
            data = self.video(fps=INLINE_VIDEO_FPS, size=INLINE_VIDEO_SIZE, audio=False)
            if len(data) <= INLINE_MAX_BYTES:
                media = (
                    f'<video controls loop muted width="{INLINE_VIDEO_SIZE[0]}" '
                    f'src="data:video/mp4;base64,{base64.b64encode(data).decode()}"></video>'
                )
        if media is None:
            data = self.png(size=INLINE_VIDEO_SIZE)
            media = f'<img width="{INLINE_VIDEO_SIZE[0]}" src="data:image/png;base64,{base64.b64encode(data).decode()}">'
        rows = "".join(
            f'<tr><th style="text-align:left">{html.escape(key)}</th><td style="text-align:left">'
            f"{html.escape(value)}</td></tr>"
            for key, value in self.summary().items()
        )
        return f"<div>{media}<table>{rows}</table></div>"

    def __repr__(self) -> str:
        return f"<SimulationResult {self.status}: {self.reason}; {self.sim_time_s:.2f} s; {self.fingerprint}>"


def simulate(
    program: str | Path | Sequence[str | Path],
    world: World | str | Path = "empty",
    robot: RobotSpec | str | None = None,
    time_s: float = 30.0,
    seed: int = 0,
    hang_after_s: float = 5.0,
) -> SimulationResult:
    """Run a program (a file, or its source as a string) or a list of them, one robot each, in a world.

    world: a shipped world's name ('line', 'maze', ...), a world file, or a World.
    robot: a RobotSpec, a shipped robot's name or a robot file (default: the world's robot).
    time_s: when to stop the run (a program that ends sooner ends it); seed: sensor noise and `random`.
    Raises ProgramError for a missing program file or a syntax error (with the line and a caret),
    WorldFileError for an unknown world or a mistake in a world file.
    """
    programs = list(program) if isinstance(program, list | tuple) else [program]
    if not programs:
        raise ValueError("simulate needs a program: a file name or the program's source")
    the_world = world if isinstance(world, World) else load_maze(find_maze(world))
    spec = _robot(robot)
    with tempfile.TemporaryDirectory(prefix="ev3sim2d-") as folder:
        paths = [_program_path(p, Path(folder), i, len(programs)) for i, p in enumerate(programs)]
        run = run_programs(
            paths, the_world, robot=spec, time_limit_s=time_s, seed=seed, hang_after_s=hang_after_s
        )
    unstartable = start_failure(run)
    if unstartable is not None:
        raise ProgramError(unstartable)
    if run.trace is None:
        raise RuntimeError(f"the run left no record: {run.reason}")
    return SimulationResult(run)


def _program_path(program: str | Path, folder: Path, index: int, count: int) -> Path:
    """A program file's path; a source string is written to a folder of its own (all its brick may read)."""
    if isinstance(program, Path) or (isinstance(program, str) and _looks_like_path(program)):
        path = Path(program)
        if not path.is_file():
            raise ProgramError(
                f"{path}: no such program file (from {os.getcwd()}); give the path of a .py file, "
                "or the program's source as a string"
            )
        return path
    source = textwrap.dedent(program)
    name = f"program {index + 1}" if count > 1 else "program"
    try:
        compile(source, f"<{name}>", "exec", dont_inherit=True)
    except SyntaxError as exc:
        raise ProgramError(
            f"the {name} given as source, line {exc.lineno}: {exc.msg}\n{source_with_caret(exc)}"
        ) from None
    own = folder / f"program{index + 1}"
    own.mkdir()
    path = own / "program.py"
    path.write_text(source, encoding="utf-8")
    return path


def _looks_like_path(text: str) -> bool:
    return "\n" not in text and (text.endswith(".py") or Path(text).is_file())


def _robot(robot: RobotSpec | str | None) -> RobotSpec | None:
    if robot is None or isinstance(robot, RobotSpec):
        return robot
    found = find_robot(str(robot))
    if found is None:
        raise ValueError(
            f"no robot file {robot!r}; give a robot file's path or a shipped robot: {', '.join(shipped_robot_names())}"
        )
    return load_robot(found)
