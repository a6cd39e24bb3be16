"""A live run: programs drive their robots while someone watches, pauses, steps, reloads, drags a
robot and edits the world (`ev3sim2d live`, docs/live.md).

The run is the run of `ev3sim2d run` (run.py: each program in a sandboxed brick, session.py's
lockstep over virtual time), advanced in steps by a thread of its own: at the wall clock's pace times
`speed` (None: as fast as it goes), one step at a time on request, or not at all while paused.
Commands come from other threads (the page's server) and are carried out by that thread between two
steps, so the world never changes inside a tick.  Each change a hand makes to the world is recorded
in the trace (Simulation.place_robot, set_cell), so a replay of the trace shows the live session as
it went; without them a live run is the run `run` gives, trace for trace.  What the page shows is a
state the thread publishes after each step: reading it never waits for the simulation, so a hung or
crashed program never holds the page up.
"""

from __future__ import annotations

import queue
import threading
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from ..devices.motor import state_text
from ..results.trace import Trace
from ..simulator.brick_port import BrickPort
from ..simulator.bricks import BrickLimits, BrickProcess, brick_welcome, start_brick
from ..simulator.cores import RunCores
from ..simulator.program import Program, ProgramError
from ..simulator.run import (
    await_hello,
    new_simulation,
    program_error,
    ran_as,
    robot_names,
    robot_specs,
    run_result,
    shown_file,
)
from ..simulator.session import Session
from ..simulator.simulation import check_place
from ..world.cell import Cell
from ..world.maze_file import parse_maze
from ..world.pose import Pose
from ..world.robot_spec import RobotSpec, parse_robot, robot_mapping_text, robot_yaml, shipped_robots_dir
from ..world.world import World
from ..world.yaml_source import read_text_file

MAX_STEP_US = 50_000  # at most this much simulated time between two looks at the commands
FAST_SPEED = 10.0  # from this many times real time, the simulator and the bricks spin as they wait (_fast)
FRAME_S = 1 / 60  # how often a paced run looks at the clock when it is ahead of it
MIN_SPEED, MAX_SPEED = 0.1, 50.0
PRINTED_KEPT = 200  # printed lines in the published state (all are in the trace)
COMMAND_TIMEOUT_S = 90.0  # a command waits this long for the run's thread (a brick starting is slow)
WATCH_EVERY_S = 0.5


class LiveError(ValueError):
    """A command that cannot be carried out (a robot into a wall, a speed out of range): says why."""


class LiveRun:
    """Programs on robots in a world, advanced live; see the module docstring."""

    def __init__(
        self,
        programs: Sequence[str | Path],
        world: World,
        robots: RobotSpec | Sequence[RobotSpec | None] | None = None,
        speed: float | None = 1.0,
        seed: int = 0,
        time_limit_s: float | None = None,
        hang_after_s: float = 5.0,
        watch: bool = True,
        arguments: Sequence[str] = (),
        debug: str | None = None,
        debugger=None,
    ) -> None:
        """watch: reload by itself when a program file changes on disk.  arguments: every program's
        command line after its name (its sys.argv[1:]).  debug, debugger: as run_programs takes them
        (breakpoint() stops the program in its brick's debugger, and debugger is the front end it asks);
        while a program is stopped, the state says where (`debugging`) and the whole world waits."""
        self.programs = [Path(p) for p in programs]
        self.arguments = [str(a) for a in arguments]
        self.debug = debug
        self.debugger = debugger
        self.debugging: str | None = None  # where a program is stopped in its debugger: prog.py:12
        for path in self.programs:
            Program(path)  # ProgramError now, for a file that is missing (a syntax error shows on the page)
        if len(self.programs) > len(world.starts):
            raise ProgramError(
                f"{len(self.programs)} programs but the world '{world.name}' has {len(world.starts)} "
                "start pose(s); add starts to the world file or run fewer programs"
            )
        self._original_text = world.text
        self.world = world
        self.starts: list[Pose] = list(world.starts[: len(self.programs)])
        self.robots = robots
        self._robot_edits: dict[int, RobotSpec] = {}  # robots changed on the page (set_robot), by index
        self.speed = _checked_speed(speed)
        self.seed = seed
        self.limit_us = None if time_limit_s is None else int(round(time_limit_s * 1e6))
        self.hang_after_s = hang_after_s
        self.watch = watch
        self.run_number = 0
        self.world_version = 0
        self.status = "starting"  # starting, running, paused, ended
        self.error: dict | None = None
        self.last_trace: Trace | None = None  # the trace of the last run that ended
        self._sim = None
        self._session: Session | None = None
        self._cores: RunCores | None = None  # where the run's processes run (simulator/cores.py)
        self._ports: list[BrickPort] = []
        self._bricks: list[BrickProcess] = []
        self._shown: list[tuple[str, str]] = []
        self._paused_by_user = False
        self._pace = (time.perf_counter(), 0)  # (wall clock, world time) the pace counts from
        self._commands: queue.Queue = queue.Queue()
        self._state_lock = threading.Lock()
        self._state: dict = {
            "status": "starting", "run": 0, "t_s": 0.0, "speed": self.speed, "world_version": 0,
            "time_limit_s": None, "robots": [], "printed": [], "printed_count": 0, "interventions": 0,
            "error": None,
        }  # fmt: skip
        self._thread: threading.Thread | None = None
        self._closing = False
        self._mtimes = self._program_mtimes()
        self._events_seen = 0  # the trace's events read so far (the LCD frames, the interventions)
        self._lcd_frames: list[int | None] = []
        self._interventions = 0

    # ------------------------------------------------------------------ life
    def start(self, paused: bool = False) -> None:
        """Start the programs and the run's thread (paused: at 0 s, until resume)."""
        self._paused_by_user = paused
        self._thread = threading.Thread(target=self._loop, name="ev3sim2d-live", daemon=True)
        self._thread.start()

    def close(self) -> Trace | None:
        """End the run (its trace is kept: last_trace) and stop every brick."""
        if self._thread is not None and self._thread.is_alive():
            self._closing = True
            self._commands.put(None)
            self._thread.join(timeout=30)
        return self.last_trace

    # -------------------------------------------------------------- commands
    def pause(self) -> dict:
        return self._do(self._pause)

    def resume(self) -> dict:
        return self._do(self._resume)

    def step(self, ms: float | None = None, ticks: int | None = None) -> dict:
        """Run on by one tick (ticks=1) or ms of simulated time (default 100 ms), then stay paused."""
        return self._do(lambda: self._step(ms, ticks))

    def set_speed(self, speed: float | None) -> dict:
        """Times real time (0.1 to 50), or None: as fast as it goes."""
        return self._do(lambda: self._set_speed(_checked_speed(speed)))

    def reload(self) -> dict:
        """Read the programs again and start over, keeping the world's edits and the robots' places."""
        return self._do(self._reload)

    def reset(self) -> dict:
        """Start over with the world file's world and starts, and the programs read again."""
        return self._do(self._reset)

    def move_robot(self, index: int, x_cm: float, y_cm: float, heading_deg: float) -> dict:
        """Pick robot `index` (0, 1, ...) up and put it down there; the physics takes it from there."""
        return self._do(lambda: self._move(index, float(x_cm), float(y_cm), float(heading_deg)))

    def set_cell(self, col: int, row: int, cell: Cell) -> dict:
        """Change a cell of the world (a wall, a shade, a colour), now and for every reload."""
        return self._do(lambda: self._set_cell(int(col), int(row), cell))

    def set_robot(self, index: int, robot: str | dict | RobotSpec) -> dict:
        """Change robot `index` (0, 1, ...): a robot file's text, or its mapping, read and checked as a
        robot file is (a WorldFileError with the line and the fix otherwise).  Only while paused or
        ended: the run starts over paused at 0 s with it, keeping the world's edits and the robots'
        places (like reload).  Reset forgets it."""
        spec = robot if isinstance(robot, RobotSpec) else parse_robot(_robot_text(robot), "the page's robot")
        return self._do(lambda: self._set_robot(index, spec))

    def robot_spec(self, index: int) -> RobotSpec:
        """The robot `index` runs as (set_robot's, else the one given or the world's)."""
        self._check_index(index)
        return self._specs()[index]

    def robot_text(self, index: int) -> str:
        """Robot `index` as a robot file's text: its own file's as it is, unless changed here."""
        spec = self.robot_spec(index)
        if index not in self._robot_edits and spec.source and spec.source.endswith((".yaml", ".yml")):
            try:
                text = read_text_file(spec.source)
                if parse_robot(text, spec.source) == spec:
                    return text
            except (OSError, ValueError):
                pass
        return robot_yaml(spec)

    def robot_file(self, index: int) -> Path | None:
        """The robot file of the user's that robot `index` came from; None for a shipped robot, one
        written inside a world file, or one changed on the page."""
        spec = self.robot_spec(index)
        if not spec.source or not spec.source.endswith((".yaml", ".yml")):
            return None
        path = Path(spec.source).resolve()
        if shipped_robots_dir() in path.parents or not path.is_file():
            return None
        try:
            parse_robot(read_text_file(path), str(path))  # a world file's inline robot is not a robot file
        except (OSError, ValueError):
            return None
        return path

    def adopt_robot_file(self, index: int, path: Path) -> None:
        """Robot `index` was saved to `path`: that is its file now (where Save writes it next time)."""
        self._do(lambda: self._adopt(index, path))

    def lcd_frame(self, frame: int) -> bytes | None:
        """The current run's LCD frame `frame` (178 x 128 bytes of grey), or None; never waits."""
        sim = self._sim
        frames = sim.trace.lcd_frames if sim is not None else []
        return frames[frame] if 0 <= frame < len(frames) else None

    def state(self) -> dict:
        """What the page shows: time, status, every robot's pose and devices, printed lines, the error."""
        with self._state_lock:
            return self._state

    def world_text(self) -> str:
        """The world as a world file, with the edits (what `save` writes)."""
        return self._do(lambda: self.world.text)

    # ------------------------------------------------------------ the thread
    def _do(self, action: Callable[[], object]) -> dict | str:
        """Carry out an action on the run's thread; its result, or LiveError saying why not."""
        if self._thread is None or not self._thread.is_alive():
            raise LiveError("the live run is not running")
        done = threading.Event()
        box: dict = {}

        def job() -> None:
            try:
                box["value"] = action()
            except (LiveError, ValueError, IndexError) as err:
                box["error"] = LiveError(str(err))
            finally:
                done.set()

        self._commands.put(job)
        if not done.wait(COMMAND_TIMEOUT_S):
            raise LiveError("the live run did not answer in time")
        if "error" in box:
            raise box["error"]
        value = box.get("value")
        return self.state() if value is None else value  # a command's new state; world_text's text

    def _loop(self) -> None:
        try:
            self._begin()
            watched = time.monotonic()
            while not self._closing:
                self._take_commands(block=not self._running())
                if self._closing:
                    break
                if self._running():
                    self._advance_paced()
                if self.watch and time.monotonic() - watched > WATCH_EVERY_S:
                    watched = time.monotonic()
                    if self._program_mtimes() != self._mtimes:
                        self._reload()
        finally:
            self._end()

    def _running(self) -> bool:
        return self.status == "running"

    def _take_commands(self, block: bool) -> None:
        timeout = WATCH_EVERY_S if block else 0.0
        while True:
            try:
                job = self._commands.get(block=timeout > 0, timeout=timeout or None)
            except queue.Empty:
                return
            if job is None:
                self._closing = True
                return
            job()
            timeout = 0.0

    # -------------------------------------------------------------- a run
    def _begin(self) -> None:
        """Start the programs in their bricks, at the robots' places, at 0 s."""
        self.run_number += 1
        self.error = None
        self._mtimes = self._program_mtimes()
        count = len(self.programs)
        sim, presses = new_simulation(self.world, count, self._specs(), self.seed, None, self.starts)
        names = robot_names(count)
        self._sim = sim
        self._events_seen, self._lcd_frames, self._interventions = 0, [None] * count, 0
        self._ports, self._bricks, self._shown = [], [], []
        limits = BrickLimits()
        printed: list = []
        self._cores = RunCores(count, spin=True)
        for i, path in enumerate(self.programs):
            real = path.resolve()
            brick, read_paths = start_brick([real.parent], spin=self._fast(), limits=limits, program=real)
            self._cores.brick_started(i, brick.popen.pid)
            self._shown.append((str(path), ran_as(real, brick)))
            self._bricks.append(brick)
            welcome = brick_welcome(
                brick,
                read_paths,
                real,
                names[i],
                sim.tick_us,
                self.seed,
                limits,
                arguments=self.arguments,
                debug=self.debug if self.debugger is not None else None,
            )
            brick.channel.send(welcome)
            self._ports.append(BrickPort(i, sim.robots[i], brick.channel, sim.trace, presses, printed))
            if self.debugger is not None:
                shown, real_path = self._shown[-1]
                self._ports[-1].debugger = lambda event, i=i, shown=shown, real=real_path: self._stopped(
                    i, shown, real, event
                )
        for port in self._ports:
            await_hello(port)
        self._cores.start()  # (this thread runs the session)
        self._session = Session(sim, self._ports, self.limit_us, self.hang_after_s, printed, None)
        self._session.set_spin(self._fast())
        self.status = "paused" if self._paused_by_user else "running"
        self._pace = (time.perf_counter(), 0)
        self._check_ended()
        self._publish()

    def _stopped(self, index: int, shown: str, real: str, event: dict) -> dict:
        """A program stopped in its brick's debugger: the page says where, the front end says what next."""
        if event.get("event") == "stopped":
            self.debugging = f"{shown_file(event.get('file', ''), shown, real)}:{event.get('line', 0)}"
            self._publish()
        try:
            command = self.debugger(index, shown, real, event)
        except KeyboardInterrupt:  # (quit at the prompt: this program stops no more, the run goes on)
            self._ports[index].debugger = None
            command = {"cmd": "continue"}
        if command.get("cmd") in ("continue", "step", "next", "return"):
            self.debugging = None
            self._publish()
        return command

    def _stop_bricks(self) -> None:
        for brick in self._bricks:
            brick.stop()
        self._bricks = []
        if self._cores is not None:
            self._cores.end()
            self._cores = None

    def _fast(self) -> bool:
        """Whether the simulator and the bricks spin as they wait for each other: only when the run goes as
        fast as it can, or nearly (at FAST_SPEED times real time or more); a run at the clock's pace waits
        for the clock most of the time, and spinning would only burn the cores then."""
        return self.speed is None or self.speed >= FAST_SPEED

    def _finish(self) -> None:
        """The run is over (every program ended, the time limit, or a reload): keep its trace."""
        session, sim = self._session, self._sim
        if session is None or sim is None:
            return
        session.finish()
        self._stop_bricks()
        result = run_result(sim, self._shown, self._ports, [None] * len(self._ports), 0.0, session)
        self.last_trace = result.trace
        self._session = None
        self._publish()

    def _end(self) -> None:
        if self._session is not None:
            self._finish()
        self._stop_bricks()
        self.status = "ended"
        self._publish()

    def _advance_paced(self) -> None:
        session = self._session
        if session is None:
            return
        now_us = session.world_us
        if self.speed is None:
            target = now_us + MAX_STEP_US
        else:
            wall, world = self._pace
            target = min(world + int((time.perf_counter() - wall) * self.speed * 1e6), now_us + MAX_STEP_US)
        if target < now_us + session.sim.tick_us:
            time.sleep(FRAME_S / 2)  # ahead of the clock: the page has time to draw
            return
        self._advance(target)

    def _advance(self, target_us: int) -> None:
        over = self._session.advance(target_us)
        self._check_ended()
        if over and self.status != "ended":
            self.status = "ended"
            self._finish()
        else:
            self._publish()

    def _check_ended(self) -> None:
        """A program that failed pauses the run, with its error (file and line) for the page."""
        if self.error is not None:
            return
        for port, (shown, real) in zip(self._ports, self._shown, strict=False):
            found = program_error(port, shown, real)
            if found is None and port.gone is not None and port.gone != "time limit":
                found = {
                    "type": "Stopped",
                    "message": port.gone,
                    "file": shown,
                    "line": None,
                    "traceback": "",
                }
            if found is not None:
                found["robot"] = port.index + 1
                self.error = found
                if self.status == "running":
                    self.status = "paused"
                return

    # ------------------------------------------------------- the commands
    def _pause(self) -> None:
        if self.status == "running":
            self.status = "paused"
            self._paused_by_user = True
        self._publish()

    def _resume(self) -> None:
        if self.status == "paused" and self._session is not None:
            self.status = "running"
            self._paused_by_user = False
            self._pace = (time.perf_counter(), self._session.world_us)
        self._publish()

    def _step(self, ms: float | None, ticks: int | None) -> None:
        if self._session is None:
            raise LiveError("the run is over: reload to run it again")
        if self.status == "running":
            self.status = "paused"
        self._paused_by_user = True
        tick = self._session.sim.tick_us
        span = (
            tick * max(1, int(ticks)) if ticks is not None else int(round((100 if ms is None else ms) * 1000))
        )
        if not 0 < span <= 60_000_000:
            raise LiveError("a step is 1 tick to 60 s of simulated time")
        self._advance(self._session.world_us + span)

    def _set_speed(self, speed: float | None) -> None:
        self.speed = speed
        if self._session is not None:
            self._pace = (time.perf_counter(), self._session.world_us)
            self._session.set_spin(self._fast())
        self._publish()

    def _reload(self) -> None:
        if self._session is not None:
            self._finish()
        self._stop_bricks()
        self._paused_by_user = self.status == "paused" and self._paused_by_user
        self._begin()

    def _reset(self) -> None:
        self._robot_edits.clear()
        self.world = parse_maze(self._original_text, self.world.name)
        self.starts = list(self.world.starts[: len(self.programs)])
        self.world_version += 1
        self._reload()

    def _check_index(self, index: int) -> None:
        if not 0 <= index < len(self.programs):
            raise LiveError(f"there is no robot {index + 1}: robots are 1 to {len(self.programs)}")

    def _specs(self) -> list[RobotSpec]:
        specs = robot_specs(self.world, len(self.programs), self.robots)
        return [self._robot_edits.get(i, spec) for i, spec in enumerate(specs)]

    def _set_robot(self, index: int, spec: RobotSpec) -> None:
        self._check_index(index)
        if self.status not in ("paused", "ended"):
            raise LiveError(
                "pause the run first: a robot is changed while paused (it then starts over at 0 s)"
            )
        before = self._robot_edits.get(index)
        self._robot_edits[index] = spec
        self._paused_by_user = True
        if self._session is not None:
            self._finish()
        self._stop_bricks()
        try:
            self._begin()
        except Exception:  # the world cannot take this robot (e.g. its body in a wall): the old one back
            if before is None:
                self._robot_edits.pop(index)
            else:
                self._robot_edits[index] = before
            self._begin()
            raise

    def _adopt(self, index: int, path: Path) -> None:
        import dataclasses

        self._robot_edits[index] = dataclasses.replace(self.robot_spec(index), source=str(path))

    def _move(self, index: int, x_cm: float, y_cm: float, heading_deg: float) -> None:
        self._check_index(index)
        check_place(self.world, index, x_cm, y_cm, heading_deg)  # (also where the run is over)
        if self._session is not None:
            self._sim.place_robot(index, x_cm, y_cm, heading_deg)
        self.starts[index] = Pose(x_cm, y_cm, heading_deg)  # where a reload starts it
        if self._session is None:  # the run is over: a new one starts from here, paused
            self._paused_by_user = True
            self._begin()
        self._publish()

    def _set_cell(self, col: int, row: int, cell: Cell) -> None:
        if self._session is not None:
            self._sim.set_cell(col, row, cell)  # (it changes self.world too)
        else:
            self.world.set_cell(col, row, cell)
        self.world_version += 1
        self._publish()

    # ------------------------------------------------------------ the state
    def _program_mtimes(self) -> list[float]:
        found = []
        for path in self.programs:
            try:
                found.append(path.stat().st_mtime)
            except OSError:
                found.append(-1.0)
        return found

    def _read_events(self, trace: Trace | None) -> None:
        """The trace's new events: each robot's last LCD frame, and how many interventions."""
        if trace is None:
            return
        events = trace.events
        for _t, robot, kind, data in events[self._events_seen :]:
            if kind == "lcd" and 0 <= robot < len(self._lcd_frames):
                self._lcd_frames[robot] = data["frame"]
            elif kind in ("place", "cell"):
                self._interventions += 1
        self._events_seen = len(events)

    def _publish(self) -> None:
        sim, session = self._sim, self._session
        trace = sim.trace if sim is not None else None
        self._read_events(trace)
        printed = trace.output[-PRINTED_KEPT:] if trace is not None else []
        state = {
            "t_s": session.world_us / 1e6 if session is not None else _last_time(trace),
            "status": self.status,
            "speed": self.speed,
            "run": self.run_number,
            "world_version": self.world_version,
            "time_limit_s": None if self.limit_us is None else self.limit_us / 1e6,
            "robots": [_robot_state(i, robot, self._lcd_frames[i]) for i, robot in enumerate(sim.robots)]
            if sim is not None
            else [],
            "printed": [
                {"t_s": line.t_s, "robot": line.robot + 1, "stream": line.stream, "text": line.text}
                for line in printed
            ],
            "printed_count": len(trace.output) if trace is not None else 0,
            "interventions": self._interventions,
            "error": self.error,
            "debugging": self.debugging,
        }
        with self._state_lock:
            self._state = state


def _last_time(trace: Trace | None) -> float:
    return trace.times[-1] if trace is not None and trace.times else 0.0


def _robot_text(robot: str | dict) -> str:
    """A robot file's text, or a robot file's mapping (as JSON gives it) written as YAML."""
    if isinstance(robot, str):
        return robot
    if isinstance(robot, dict):  # held to a robot file's limits before it is written out (no RecursionError)
        return robot_mapping_text(robot, "the page's robot")
    raise LiveError("a robot is a robot file's text or its mapping (docs/world-files.md)")


def _robot_state(index: int, robot, lcd_frame: int | None = None) -> dict:
    """A robot as the page draws it: pose, and each device's last values (reading none: no side effect)."""
    sensors = []
    for port, sensor in robot.sensors.items():
        last = sensor.samples[-1] if sensor.samples else None
        sensors.append(
            {
                "port": port,
                "kind": sensor.spec.kind,
                "mode": sensor.mode,
                "values": list(last[2]) if last else [],
                "angle_deg": sensor.spec.angle_deg,
                "radius_cm": sensor.spec.radius_cm,
                "facing": sensor.spec.facing,
                "aim_deg": sensor.spec.aim_deg,
            }
        )
    motors = [
        {"port": port, "kind": motor.kind, "speed": motor.speed, "position": motor.position,
         "state": state_text(motor.state_bits)}
        for port, motor in robot.motors.items()
    ]  # fmt: skip
    leds = {name: led.brightness for name, led in robot.brick.leds.items()}
    return {
        "number": index + 1,
        "name": robot.name,
        "x_cm": robot.x,
        "y_cm": robot.y,
        "heading_deg": robot.heading_rad * 57.29577951308232,
        "sensors": sensors,
        "motors": motors,
        "leds": leds,
        "lcd_frame": lcd_frame,
        "body": {**robot.spec.body.__dict__, "color": list(robot.spec.color)},
    }


def _checked_speed(speed: float | None) -> float | None:
    if speed is None:
        return None
    speed = float(speed)
    if not MIN_SPEED <= speed <= MAX_SPEED:
        raise LiveError(
            f"speed {speed:g}: it is {MIN_SPEED:g} to {MAX_SPEED:g} times real time, or as fast as it goes"
        )
    return speed
