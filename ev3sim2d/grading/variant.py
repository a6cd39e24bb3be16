"""One variant of a lesson: the world a program is graded in, with its start, robot, sensor noise and seed.

Variants keep a program honest: another start pose, a mirrored or different
maze, noisy sensors with another seed.  The visible variants are in lesson.yaml;
the hidden ones, graded like the others but never shipped nor shown to students,
in `hidden/hidden.yaml` (see lesson.py), whose worlds and robots are looked for in
that folder first.  Reports call a hidden variant only "hidden variant N".

A variant may have other robots besides the student's (`others:`), each driven by a
program of the lesson's own at a start pose of its own; robot i of the run starts at
the world's start i, so the student's robot and the others take starts 1..n between
them.  The student's program may read only the submission; each of the lesson's
programs only its own file.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

from ..world.maze_file import load_maze, shipped_mazes_dir
from ..world.pose import Pose
from ..world.robot_spec import SENSOR_KINDS, RobotSpec, find_robot, load_robot, shipped_robot_names
from ..world.world import World
from ..world.yaml_source import Fields, Node, foreign_path_hint, written_path

VARIANT_KEYS = (
    "name",
    "world",
    "description",
    "hidden",
    "start",
    "robot",
    "noise",
    "seed",
    "time_s",
    "others",
)
STUDENT = "student"  # the name checks and reports give the student's robot
OTHERS_EXAMPLE = "others: [{name: pacer, program: pacer.py, start: 1}]"


@dataclass(frozen=True)
class OtherRobot:
    """A robot of the run driven by one of the lesson's own programs, not the student's."""

    name: str  # what checks (`robot: pacer`) and reports call it
    program: Path  # a trusted file of the lesson (or of its hidden folder); only its own brick reads it
    start: int  # the world's start pose it takes, counted from 1


VARIANT_EXAMPLE = "- {name: mirrored, world: maze-mirrored.yaml}"
START_EXAMPLE = "start: {x_cm: 60, y_cm: 40, heading_deg: 90}"


@dataclass
class Variant:
    """A world (file), optionally with another start, robot, sensor noise, seed and time limit."""

    name: str
    world_path: Path
    time_s: float
    seed: int = 0
    hidden: bool = False
    description: str = ""
    start: Pose | None = None
    robot: RobotSpec | None = None  # None: the world's own robot
    noise: dict[str, float] = field(default_factory=dict)
    hidden_number: int = 0  # 1, 2, ... for hidden variants, in the order of hidden.yaml
    student_start: int = 1  # the world's start pose the student's robot takes, counted from 1
    others: list[OtherRobot] = field(default_factory=list)  # robots driven by the lesson's own programs
    _world: World | None = field(default=None, repr=False)

    @property
    def report_name(self) -> str:
        """The name reports show: the variant's own, or "hidden variant N" (a name could give its world away)."""
        return f"hidden variant {self.hidden_number}" if self.hidden else self.name

    def world(self) -> World:
        """The world to run in, with this variant's start, robot and noise (read once)."""
        if self._world is None:
            world = load_maze(self.world_path)
            robot = self.robot or world.robot
            if self.noise:
                robot = with_noise(robot, self.noise)
            starts = list(world.starts)
            if self.start is not None:  # another start for the student's robot
                starts[self.student_start - 1] = self.start
            self._world = dataclasses.replace(world, robot=robot, starts=starts)
        return self._world

    @property
    def robot_names(self) -> list[str]:
        """The name of each robot of the run, in the order of their starts (robot i at start i + 1)."""
        names = {self.student_start: STUDENT, **{other.start: other.name for other in self.others}}
        return [names[start] for start in sorted(names)]

    @property
    def student_index(self) -> int:
        """The student's robot's index among the run's robots (its start - 1)."""
        return self.student_start - 1

    def robot_index(self, name: str | None) -> int:
        """The index of the robot called `name` in the run (None: the student's)."""
        return self.robot_names.index(name or STUDENT)

    def programs(self, submission: Path) -> list[Path]:
        """The program of each robot in the order of their starts: the submission drives the student's."""
        by_start = {self.student_start: submission, **{o.start: o.program for o in self.others}}
        return [by_start[start] for start in sorted(by_start)]

    def readable(self, submission: Path) -> list[list[Path]]:
        """What each robot's brick may read besides Python: the submission (file or folder) for the
        student's, and only its own file for each of the lesson's programs."""
        by_start = {self.student_start: [submission], **{o.start: [o.program] for o in self.others}}
        return [by_start[start] for start in sorted(by_start)]


def with_noise(robot: RobotSpec, noise: dict[str, float]) -> RobotSpec:
    """The robot with the given noise (standard deviation by sensor kind) on its sensors of those kinds."""
    sensors = tuple(
        dataclasses.replace(s, noise=noise[s.kind]) if s.kind in noise else s for s in robot.sensors
    )
    return dataclasses.replace(robot, sensors=sensors)


def _folders(folders: Path | list[Path]) -> list[Path]:
    return [folders] if isinstance(folders, Path) else list(folders)


def _named(folders: list[Path]) -> str:
    return " or ".join(str(folder) for folder in folders)


def find_world_file(value: str, folders: Path | list[Path]) -> Path | None:
    """A world file in the given folders, in order (with or without .yaml), else a shipped maze by name;
    `value` is a path as written in a file on any system ('\\' or '/' between folders)."""
    candidate = written_path(value)
    places = [
        place
        for folder in _folders(folders)
        for place in (folder / candidate, folder / written_path(f"{value}.yaml"))
    ]
    stem = candidate.stem if candidate.suffix in (".yaml", ".yml") else candidate.name
    places.append(shipped_mazes_dir() / f"{stem}.yaml")
    return next((p for p in places if p.is_file()), None)


def read_robot(node: Node, folders: Path | list[Path]) -> RobotSpec:
    """`robot: FILE` (in the given folders, in order) or the name of a shipped robot."""
    value = node.as_text("robot", "robot: ev3-driving-base").strip()
    folders = _folders(folders)
    written = written_path(value)
    path = next((found for f in folders if (found := find_robot(written, f)) is not None), None)
    if path is None:
        raise node.error(
            f"no robot file '{value}' in {_named(folders)} and no shipped robot by that name; "
            f"shipped robots: {', '.join(shipped_robot_names())}{foreign_path_hint(value)}"
        )
    return load_robot(path)


def read_others(node: Node, folders: Path | list[Path], student_start: int) -> list[OtherRobot]:
    """`others: [{name: pacer, program: pacer.py, start: 1}]`: robots driven by the lesson's programs
    (files in the given folders, in order), each at a start of its own, not the student's."""
    folders = _folders(folders)
    others: list[OtherRobot] = []
    for item in node.as_list("others", OTHERS_EXAMPLE):
        if not item.is_mapping:
            raise item.error(
                f"each of `others` is a mapping like `{OTHERS_EXAMPLE[9:-1]}`, got {item.describe()}"
            )
        fields = item.as_fields("others", ("name", "program", "start"), OTHERS_EXAMPLE)
        value = fields.text("program", example="program: pacer.py").strip()
        written = written_path(value)
        program = next((f / written for f in folders if (f / written).is_file()), None)
        if program is None or program.suffix != ".py":
            raise fields.get("program").error(
                f"no program '{value}' in {_named(folders)}; give a .py file of the lesson's folder"
                + foreign_path_hint(value)
            )
        name = fields.text("name", default=program.stem, example="name: pacer").strip()
        if not name or any(c in name for c in "/\\ ") or name == STUDENT:
            raise (fields.get("name") or fields.get("program")).error(
                f"a robot's name is one word other than '{STUDENT}' (the student's robot), got {name!r}; "
                "e.g. `name: pacer`"
            )
        start = fields.integer("start", example="start: 1")
        if start < 1 or start == student_start:
            raise fields.get("start").error(
                f"'start' is the number of a start pose of the world (1 is the first) other than the "
                f"student's ({student_start}), got {start}"
            )
        for other in others:
            if other.name == name:
                raise item.error(f"two of `others` are named '{name}'; give each its own `name:`")
            if other.start == start:
                raise fields.get("start").error(f"'{other.name}' already takes start {start}; give another")
        others.append(OtherRobot(name, program.resolve(), start))
    return others


def check_starts(node: Node, world: World, student_start: int, others: list[OtherRobot]) -> None:
    """The robots of the run take the world's starts 1..n between them, and the world has them."""
    taken = sorted([student_start, *(o.start for o in others)])
    if taken != list(range(1, len(taken) + 1)):
        raise node.error(
            f"the robots take starts {', '.join(map(str, taken))} of the world: robot i of a run starts at "
            f"the world's start i, so {len(taken)} robots take starts 1 to {len(taken)}"
        )
    if len(world.starts) < len(taken):
        raise node.error(
            f"{len(taken)} robots (the student's and {len(others)} of `others`) but the world {world.source} "
            f"has {len(world.starts)} start pose(s); give it one for each robot"
        )


def read_noise(node: Node) -> dict[str, float]:
    """`noise: {color: 2, ultrasonic: 1}`: standard deviation by sensor kind, in the sensor's unit."""
    fields = node.as_fields("noise", SENSOR_KINDS, "noise: {color: 2}")
    noise = {}
    for kind in fields:
        value = fields.number(kind, unit="the sensor's own unit", example=f"{kind}: 2")
        if value < 0:
            raise fields.get(kind).error(
                f"noise is a standard deviation and cannot be negative, got {value:g}"
            )
        noise[kind] = value
    return noise


def read_start(node: Node, world: World) -> Pose:
    """A start pose (`{x_cm, y_cm, heading_deg}` or `{cell: [col, row], heading_deg}`) on the world's floor."""
    fields = node.as_fields("start", ("cell", "x_cm", "y_cm", "heading_deg"), START_EXAMPLE)
    heading = fields.number("heading_deg", default=0.0, unit="degrees", example="heading_deg: 90")
    grid = world.grid
    if "cell" in fields:
        if "x_cm" in fields or "y_cm" in fields:
            raise node.error("give the start either as `cell: [col, row]` or as `x_cm` and `y_cm`, not both")
        col, row = (int(v) for v in fields.get("cell").as_numbers("cell", 2, example="cell: [1, 1]"))
        if not grid.contains(col, row) or grid.is_wall(col, row):
            raise fields.get("cell").error(f"start cell [{col}, {row}] is not a floor cell of {world.source}")
        x, y = grid.cell_center(col, row)
        return Pose(x, y, heading)
    x = fields.number("x_cm", unit="cm", example="x_cm: 60")
    y = fields.number("y_cm", unit="cm", example="y_cm: 40")
    index = grid.cell_index_at(x, y)
    if index is None or grid.is_wall(*index):
        raise node.error(f"start x_cm {x:g}, y_cm {y:g} is not on the floor of {world.source}", column=False)
    return Pose(x, y, heading)


def variant_from_node(
    node: Node,
    folders: Path | list[Path],
    default_time_s: float,
    default_seed: int,
    default_robot: RobotSpec | None,
    hidden: bool = False,
    student_start: int = 1,
    default_others: list[OtherRobot] | None = None,
) -> tuple[Variant, Fields]:
    """One entry of `variants:` (of lesson.yaml, or with `hidden` of hidden.yaml); the world, start and
    robot are read (and checked) now, worlds and robots looked for in `folders` in order."""
    folders = _folders(folders)
    if not node.is_mapping:
        raise node.error(f"each variant is a mapping like `{VARIANT_EXAMPLE}`, got {node.describe()}")
    fields = node.as_fields("variant", VARIANT_KEYS, VARIANT_EXAMPLE)
    if "hidden" in fields:
        written = fields.boolean("hidden")
        if not hidden and written:
            raise fields.key("hidden").error(
                "hidden variants live apart from lesson.yaml, in hidden/hidden.yaml next to it (never shipped, "
                "never shown to students); move this variant there, with its world files"
            )
        if hidden and not written:
            raise fields.key("hidden").error(
                "every variant in hidden.yaml is hidden; a visible variant belongs in lesson.yaml"
            )
    name = fields.text("name", example="name: mirrored").strip()
    if not name or any(c in name for c in "/\\ "):
        raise fields.get("name").error(
            f"a variant name is one word without '/', got {name!r}; e.g. `name: mirrored`"
        )
    world_node = fields.require("world", "world: maze.yaml")
    world_value = world_node.as_text("world", "world: maze.yaml").strip()
    world_path = find_world_file(world_value, folders)
    if world_path is None:
        raise world_node.error(
            f"no world file '{world_value}' in {_named(folders)} and no shipped maze by that name; "
            "give a .yaml file in the lesson's folder or a shipped maze (ev3sim2d mazes)"
            + foreign_path_hint(world_value)
        )
    time_s = fields.number("time_s", default=default_time_s, unit="simulated seconds", example="time_s: 60")
    if time_s <= 0:
        raise fields.get("time_s").error(f"'time_s' must be more than 0, got {time_s:g}")
    robot = read_robot(fields.get("robot"), folders) if "robot" in fields else default_robot
    variant = Variant(
        name=name,
        world_path=world_path,
        time_s=time_s,
        seed=fields.integer("seed", default=default_seed, example="seed: 1"),
        hidden=hidden,
        description=fields.text("description", default="").strip(),
        robot=robot,
        noise=read_noise(fields.get("noise")) if "noise" in fields else {},
        student_start=student_start,
    )
    if "others" in fields:
        variant.others = read_others(fields.get("others"), folders, student_start)
    else:
        variant.others = list(default_others or [])
    world = load_maze(world_path)  # WorldFileError names the world file and its line
    check_starts(fields.get("others") or world_node, world, student_start, variant.others)
    if "start" in fields:
        variant.start = read_start(fields.get("start"), world)
    return variant, fields
