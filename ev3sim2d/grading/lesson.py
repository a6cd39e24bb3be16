"""A lesson: a task in one or more worlds (variants), and the checks that score it (lessons/<id>/lesson.yaml).

The folder holds `lesson.yaml`, `README.md` (the task as a student reads it),
`starter.py`, `solution.py` (python-ev3dev2), `starter_pybricks.py`, `solution_pybricks.py` (the same in
Pybricks 2.0, optional), world files the lesson needs, and optionally
`check_*.py` files with check kinds of its own.  Its hidden variants live apart,
in `hidden/hidden.yaml` with their world files (a folder a wheel never ships),
or in a teacher's private copy named with `load_lesson(..., hidden=DIR)`
(`ev3sim2d grade --hidden DIR`); without either, only the visible variants are
graded.  At least one check is a goal check (`goal: true`); the others count
only once every goal check passes.  Every mistake in lesson.yaml or hidden.yaml
is a WorldFileError naming the file, the line and what to write instead.  The
format is described in docs/lessons.md.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib.util
import inspect
import os
import sys
from dataclasses import dataclass, field
from pathlib import Path

from ..simulator.simulation import Simulation, StartBlocked
from ..world.source_error import WorldFileError
from ..world.yaml_source import Fields, Node, foreign_path_hint, load_yaml_text, read_text_file, written_path
from .check import COMMON_KEYS, Check, builtin_checks, checks_from_node
from .variant import STUDENT, OtherRobot, Variant, read_others, read_robot, variant_from_node

LESSON_FILE = "lesson.yaml"
HIDDEN_DIR = "hidden"  # lessons/<id>/hidden/: the hidden variants and their worlds, never in a wheel
HIDDEN_FILE = "hidden.yaml"
HIDDEN_KEYS = ("variants",)
LESSON_KEYS = (
    "title",
    "goal",
    "robot",
    "time_s",
    "seed",
    "limits",
    "variants",
    "checks",
    "starter",
    "solution",
    "starter_pybricks",
    "solution_pybricks",
    "student_start",
    "others",
)
LIMIT_KEYS = ("wall_s", "cpu_s", "memory_mb", "hang_s", "output_mb")
GRADER_VERSION = (
    "2"  # part of every result's key: bump it when scoring changes, so old results are not reused
)


@dataclass(frozen=True)
class Limits:
    """Safety limits on each run's process, apart from the lesson's simulated time limit.

    Unset wall and CPU limits follow the simulated time: 30 s plus a quarter of it.
    """

    wall_s: float | None = None
    cpu_s: float | None = None
    memory_mb: float = 512.0  # address space the run's process may add to what it has at the start
    hang_s: float = 3.0  # real seconds without the virtual clock moving before a program counts as stuck
    output_mb: float = 16.0  # the most a program may write to the console outside print()

    def wall_for(self, time_s: float) -> float:
        return self.wall_s if self.wall_s is not None else 30.0 + time_s / 4

    def cpu_for(self, time_s: float) -> float:
        return self.cpu_s if self.cpu_s is not None else 30.0 + time_s / 4


@dataclass
class Lesson:
    """A lesson as read from its folder."""

    id: str
    folder: Path
    title: str
    goal: str
    time_s: float
    variants: list[Variant]
    checks: list[Check]
    limits: Limits = field(default_factory=Limits)
    starter: Path | None = None
    solution: Path | None = None
    starter_pybricks: Path | None = None  # the same two in Pybricks 2.0 (LEGO's EV3 MicroPython)
    solution_pybricks: Path | None = None
    text: str = ""
    hidden_file: Path | None = None  # where the hidden variants came from (None: no hidden variants)
    hidden_text: str = ""
    student_start: int = 1  # the world's start pose the student's robot takes
    others: list[OtherRobot] = field(
        default_factory=list
    )  # the lesson's own robots (a variant may change them)

    @property
    def several_robots(self) -> bool:
        """Whether any variant's runs have robots besides the student's."""
        return any(variant.others for variant in self.variants)

    @property
    def source(self) -> Path:
        return self.folder / LESSON_FILE

    @property
    def variant_points(self) -> float:
        """The points one variant is worth (the sum of the checks' points)."""
        return sum(check.points for check in self.checks)

    @property
    def max_score(self) -> float:
        return self.variant_points * len(self.variants)

    def variant(self, name: str) -> Variant:
        for variant in self.variants:
            if variant.name == name:
                return variant
        raise KeyError(
            f"lesson {self.id!r} has no variant {name!r}; its variants: {', '.join(v.name for v in self.variants)}"
        )

    def visible_variants(self) -> list[Variant]:
        return [v for v in self.variants if not v.hidden]

    def hidden_variants(self) -> list[Variant]:
        return [v for v in self.variants if v.hidden]

    @property
    def goal_checks(self) -> list[Check]:
        return [check for check in self.checks if check.goal]

    def digest(self) -> str:
        """A hash of everything that decides a score: lesson and hidden files, check files, worlds, robots,
        grader version."""
        h = hashlib.sha256(GRADER_VERSION.encode())
        h.update(self.text.encode())
        h.update(self.hidden_text.encode())
        for path in sorted(self.folder.glob("check_*.py")):
            h.update(path.read_bytes())
        for variant in self.variants:
            for other in variant.others:  # the lesson's own programs decide a score too
                h.update(f"{other.name}:{other.start}:".encode())
                h.update(other.program.read_bytes())
            world = variant.world()
            h.update((world.text or "").encode())
            h.update(repr(dataclasses.replace(world.robot, source=None)).encode())
            h.update(repr(world.starts).encode())
            for i in range(len(world.start_robots)):  # a start's own robot decides a score too
                h.update(repr(dataclasses.replace(world.start_robot(i), source=None)).encode())
        return h.hexdigest()[:16]


# -- finding lessons ----------------------------------------------------------------------


def shipped_lessons_dir() -> Path:
    """The lessons that come with ev3sim2d (an installed copy first, else the repository's `lessons/`)."""
    package = Path(__file__).resolve().parents[1]
    for candidate in (package / "_lessons", package.parent / "lessons"):
        if candidate.is_dir():
            return candidate
    return package.parent / "lessons"


def list_shipped_lessons() -> list[str]:
    """Ids of the shipped lessons."""
    root = shipped_lessons_dir()
    return sorted(p.parent.name for p in root.glob(f"*/{LESSON_FILE}")) if root.is_dir() else []


def written_as_path(text: str | Path) -> bool:
    """Whether a lesson was named by a path (a folder separator in it, a leading `.` or `~`, or a file
    ending in .yaml) rather than by its id."""
    text = str(text)
    separators = {"/", "\\", os.sep, os.altsep or "/"}
    return (
        any(s in text for s in separators) or text.startswith((".", "~")) or text.endswith((".yaml", ".yml"))
    )


def find_lesson(name_or_path: str | Path, lessons: str | Path | None = None) -> Path:
    """A lesson folder: a path written as one (a folder or its lesson.yaml), else the lesson of that id
    in `lessons` (a teacher's folder of lessons) or among the shipped ones: never a folder that merely
    has the id's name in the working folder, which may be a student's checkout."""
    if isinstance(name_or_path, Path) or written_as_path(name_or_path):
        candidate = Path(name_or_path).expanduser()
        if candidate.is_file() and candidate.name == LESSON_FILE:
            return candidate.parent
        if (candidate / LESSON_FILE).is_file():
            return candidate
        raise WorldFileError(
            str(name_or_path), None, None, f"no lesson folder here (a folder with a {LESSON_FILE})"
        )
    name = str(name_or_path)
    for root in ([Path(lessons)] if lessons is not None else []) + [shipped_lessons_dir()]:
        if (root / name / LESSON_FILE).is_file():
            return root / name
    known = ", ".join(list_shipped_lessons()) or "none"
    where = f"in {lessons}, nor " if lessons is not None else ""
    mine = (
        f"; to grade with the folder {name} here, write ./{name}"
        if (Path(name) / LESSON_FILE).is_file()
        else ""
    )
    raise WorldFileError(
        name, None, None, f"no lesson of this id {where}shipped; shipped lessons: {known}{mine}"
    )


# -- reading ------------------------------------------------------------------------------


def find_hidden(folder: Path, hidden: str | Path | None = None) -> Path | None:
    """The hidden.yaml of the lesson in `folder`: with `hidden` (a teacher's private copy) DIR/hidden.yaml or
    DIR/<lesson id>/hidden.yaml, else the lesson's own hidden/hidden.yaml; None when there is none."""
    if hidden is None:
        own = folder / HIDDEN_DIR / HIDDEN_FILE
        return own if own.is_file() else None
    base = Path(hidden)
    for candidate in (base / HIDDEN_FILE, base / folder.name / HIDDEN_FILE, base):
        if candidate.is_file() and candidate.name == HIDDEN_FILE:
            return candidate.resolve()
    raise WorldFileError(
        str(hidden),
        None,
        None,
        f"no {HIDDEN_FILE} for lesson '{folder.name}' here: give a folder holding {HIDDEN_FILE} "
        f"(with the hidden variants' world files), or one holding {folder.name}/{HIDDEN_FILE}",
    )


def load_lesson(
    name_or_path: str | Path, hidden: str | Path | None = None, lessons: str | Path | None = None
) -> Lesson:
    """Read a lesson by folder, lesson.yaml path or id (find_lesson: in `lessons`, else shipped); worlds
    and check parameters are checked now.

    The hidden variants come from `hidden` (a folder with hidden.yaml, or with <lesson id>/hidden.yaml) if
    given, else from the lesson's own hidden/hidden.yaml if there is one; they follow the visible ones.
    """
    folder = find_lesson(name_or_path, lessons).resolve()
    path = folder / LESSON_FILE
    text = read_text_file(path)
    root = load_yaml_text(text, str(path))
    if not root.is_mapping:
        raise root.error(
            f"a lesson file is a mapping of keys like `title: Stop at the wall`, got {root.describe()}"
        )
    fields = Fields(root, "the lesson file", LESSON_KEYS)
    title = fields.text("title", example="title: Stop at the wall").strip()
    goal = " ".join(fields.text("goal", example="goal: Drive to the wall and stop 10 cm before it.").split())
    time_s = fields.number("time_s", unit="simulated seconds", example="time_s: 30")
    if time_s <= 0:
        raise fields.get("time_s").error(f"'time_s' must be more than 0, got {time_s:g}")
    seed = fields.integer("seed", default=0, example="seed: 0")
    robot = read_robot(fields.get("robot"), folder) if "robot" in fields else None
    limits = _limits(fields.get("limits")) if "limits" in fields else Limits()
    student_start = fields.integer("student_start", default=1, example="student_start: 2")
    if student_start < 1:
        raise fields.get("student_start").error(
            f"'student_start' is the number of a start pose of the worlds (1 is the first), got {student_start}"
        )
    others = read_others(fields.get("others"), folder, student_start) if "others" in fields else []
    several = (student_start, others)

    variants_node = fields.require("variants", "variants: [{name: basic, world: maze}]")
    items = variants_node.as_list("variants", "variants: [{name: basic, world: maze}]")
    if not items:
        raise variants_node.error("a lesson needs at least one variant; e.g. `- {name: basic, world: maze}`")
    variants: list[Variant] = []
    for item in items:
        _add_variant(variants, *variant_from_node(item, folder, time_s, seed, robot, False, *several))

    hidden_file = find_hidden(folder, hidden)
    hidden_text = ""
    if hidden_file is not None:
        hidden_text = read_text_file(hidden_file)
        for item in _hidden_items(hidden_text, hidden_file):
            variant, vfields = variant_from_node(
                item, [hidden_file.parent, folder], time_s, seed, robot, True, *several
            )
            variant.hidden_number = sum(v.hidden for v in variants) + 1
            _add_variant(variants, variant, vfields)

    kinds = {**builtin_checks(), **_lesson_check_kinds(folder, path)}
    checks = checks_from_node(
        fields.require("checks", "checks: [{kind: reach_region, region: goal, goal: true}]"), kinds
    )
    for variant in variants:
        world = variant.world()
        for check in checks:
            check.validate(world, variant.name)
            _check_robot(check, variant)

    return Lesson(
        id=folder.name,
        folder=folder,
        title=title,
        goal=goal,
        time_s=time_s,
        variants=variants,
        checks=checks,
        limits=limits,
        starter=_program(fields, "starter", folder),
        solution=_program(fields, "solution", folder),
        starter_pybricks=_program(fields, "starter_pybricks", folder),
        solution_pybricks=_program(fields, "solution_pybricks", folder),
        text=text,
        hidden_file=hidden_file,
        hidden_text=hidden_text,
        student_start=student_start,
        others=others,
    )


def _check_robot(check: Check, variant: Variant) -> None:
    """A check's `robot:` names a robot of every variant's runs."""
    if check.robot is None or check.robot in variant.robot_names:
        return
    node = check.nodes.get("robot")
    message = (
        f"check '{check.name}' looks at robot '{check.robot}', but variant '{variant.name}' has only "
        f"{', '.join(variant.robot_names)}; name one of them (`{STUDENT}`, the default, is the student's "
        "robot; the others are named in `others:`)"
    )
    if node is None:
        raise ValueError(message)
    raise node.error(message)


def _add_variant(variants: list[Variant], variant: Variant, fields: Fields) -> None:
    """Append the variant once its name is known to be new and its robot fits where it starts."""
    if any(v.name == variant.name for v in variants):
        raise fields.get("name").error(f"two variants are named '{variant.name}'; give each its own name")
    _check_start_fits(variant, fields.get("start") or fields.get("world"))
    variants.append(variant)


def _hidden_items(text: str, path: Path) -> list[Node]:
    """The `variants:` list of a hidden.yaml (at least one)."""
    example = "variants: [{name: far, world: far.yaml}]"
    root = load_yaml_text(text, str(path))
    if not root.is_mapping:
        raise root.error(f"a {HIDDEN_FILE} file is a mapping with the key `variants:`, got {root.describe()}")
    fields = Fields(root, f"the {HIDDEN_FILE} file", HIDDEN_KEYS)
    node = fields.require("variants", example)
    items = node.as_list("variants", example)
    if not items:
        raise node.error(f"no hidden variants; e.g. `{example}`, or remove the file")
    return items


def _check_start_fits(variant: Variant, node: Node) -> None:
    """Each robot must fit where the variant starts it (not half inside a wall)."""
    world = variant.world()
    names = variant.robot_names
    try:
        Simulation(world, [(names[i], world.start_robot(i), world.starts[i]) for i in range(len(names))])
    except StartBlocked as err:
        raise node.error(f"variant '{variant.name}': {err}") from None


def _program(fields: Fields, key: str, folder: Path) -> Path | None:
    name = fields.text(key, default=f"{key}.py", example=f"{key}: {key}.py").strip()
    path = folder / written_path(name)  # `programs\starter.py` from Windows too
    if key in fields and not path.is_file():
        raise fields.get(key).error(f"no file '{name}' in {folder}{foreign_path_hint(name)}")
    return path if path.is_file() else None


def _limits(node: Node) -> Limits:
    fields = node.as_fields("limits", LIMIT_KEYS, "limits: {wall_s: 60, memory_mb: 1024}")
    values = {}
    for key in LIMIT_KEYS:
        if key in fields:
            value = fields.number(key, example=f"{key}: 10")
            if value <= 0:
                raise fields.get(key).error(f"'{key}' must be more than 0, got {value:g}")
            values[key] = value
    return Limits(**values)


def _lesson_check_kinds(folder: Path, lesson_path: Path) -> dict[str, type[Check]]:
    """The check kinds defined in the lesson's check_*.py files (Check subclasses with a KIND)."""
    builtins = builtin_checks()
    kinds: dict[str, type[Check]] = {}
    for path in sorted(folder.glob("check_*.py")):
        module_name = f"ev3sim2d_lesson_{folder.name.replace('-', '_')}_{path.stem}"
        spec = importlib.util.spec_from_file_location(module_name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[module_name] = module
        try:
            spec.loader.exec_module(module)
        except Exception as exc:
            raise WorldFileError(
                str(path), None, None, f"cannot load this check file: {type(exc).__name__}: {exc}"
            ) from exc
        for _, cls in inspect.getmembers(module, inspect.isclass):
            if issubclass(cls, Check) and cls.KIND and cls.__module__ == module_name:
                if cls.KIND in builtins:
                    raise WorldFileError(
                        str(path),
                        None,
                        None,
                        f"check kind '{cls.KIND}' is a built-in kind; give yours another KIND",
                    )
                common = [p.name for p in cls.PARAMS if p.name in COMMON_KEYS]
                if common:
                    raise WorldFileError(
                        str(path),
                        None,
                        None,
                        f"check kind '{cls.KIND}' has a parameter named '{common[0]}', a key every check has "
                        f"({', '.join(COMMON_KEYS)}); give it another name",
                    )
                kinds[cls.KIND] = cls
    return kinds
