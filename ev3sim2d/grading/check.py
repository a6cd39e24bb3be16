"""A check: one thing a lesson scores ("reached the goal", "never touched a wall"), read from YAML.

Every kind of check is a `Check` subclass with a YAML name (`KIND`), a line of
help (`SUMMARY`) and its parameters (`PARAMS`); `@register` puts it into the
registry of built-in kinds (the modules in `checks/`), and a lesson may define
more in `check_*.py` files next to its lesson.yaml.  A check reads only the
run's record (trace and world, `RunRecord`) and answers with an `Outcome`: passed
or not, and a sentence a student understands, with the simulated time of what
decided it, and the same without numbers (`brief`) for hidden variants.

A check is either one of the lesson's goal checks (`goal: true`: the task itself)
or a secondary one (stopped, no wall contact, finished, ...), which counts only once
every goal check of the variant passes (see scoring.py).  A kind that a robot
standing still passes (`PASSES_WITHOUT_MOVING`) cannot be a goal.

In a lesson with several robots a check may name the robot it looks at (`robot: pacer`,
one of the lesson's `others`); by default it looks at the student's.  A check of another
robot is never a goal: the goal is the student's task.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar

from ..world.source_error import WorldFileError
from ..world.world import World
from ..world.yaml_source import Node
from .run_record import RunRecord
from .variant import STUDENT

REQUIRED: Any = object()
COMMON_KEYS = ("kind", "name", "points", "goal", "robot")


@dataclass(frozen=True)
class Outcome:
    """What a check found: passed or not, why (one sentence), and when (simulated seconds), if anything decided it.

    `brief` is the sentence without numbers (no distances, positions or times), shown for hidden variants
    instead of `message`, so that their results do not give their worlds away; by default "passed" or
    "did not pass" with the check's summary.
    """

    passed: bool
    message: str
    t_s: float | None = None
    brief: str | None = None


@dataclass(frozen=True)
class Param:
    """One parameter of a check kind: its YAML key, type, default and meaning (for errors and docs).

    `kind` is one of: number, seconds, cm, degrees, fraction, count, text, region, bool, choice;
    or give `read(node) -> value` for anything else (then `kind` only names it in the docs).
    """

    name: str
    kind: str
    help: str
    default: Any = REQUIRED
    choices: tuple[str, ...] = ()
    read: Callable[[Node], Any] | None = None

    @property
    def required(self) -> bool:
        return self.default is REQUIRED

    def example(self) -> str:
        samples = {
            "number": "1",
            "seconds": "10",
            "cm": "5",
            "degrees": "90",
            "fraction": "0.9",
            "count": "0",
            "text": "...",
            "region": "goal",
            "bool": "true",
        }
        value = self.choices[0] if self.choices else samples.get(self.kind, "...")
        return f"{self.name}: {value}"

    def value_of(self, node: Node) -> Any:
        """The parameter's value from its YAML node; WorldFileError (with the line) when it does not fit."""
        if self.read is not None:
            return self.read(node)
        example = self.example()
        if self.kind in ("number", "seconds", "cm", "degrees", "fraction"):
            unit = {"seconds": "simulated seconds", "cm": "cm", "degrees": "degrees"}.get(self.kind, "")
            value = node.as_number(self.name, unit, example)
            if self.kind == "fraction" and not 0 <= value <= 1:
                raise node.error(
                    f"'{self.name}' is a fraction from 0 to 1, got {value:g}; write e.g. `{example}`"
                )
            if self.kind in ("seconds", "cm") and value < 0:
                raise node.error(f"'{self.name}' cannot be negative, got {value:g}")
            return value
        if self.kind == "count":
            value = node.as_int(self.name, example)
            if value < 0:
                raise node.error(f"'{self.name}' cannot be negative, got {value}")
            return value
        if self.kind in ("text", "region"):
            return node.as_text(self.name, example)
        if self.kind == "bool":
            return node.as_bool(self.name)
        if self.kind == "choice":
            word = node.as_text(self.name, example).strip()
            if word not in self.choices:
                raise node.error(
                    f"'{self.name}' must be one of {', '.join(self.choices)}, got {node.describe()}"
                )
            return word
        raise ValueError(f"unknown parameter kind {self.kind!r} for {self.name!r}")  # our bug


# The point of the robot a check follows: its centre, its colour sensor (the spot it sees) or its front.
POINT_PARAM = Param(
    "point",
    "choice",
    "which point of the robot counts: its centre, the spot its colour sensor sees, or the middle of its front",
    default="centre",
    choices=("centre", "color-sensor", "front"),
)


class Check:
    """Base of all check kinds; an instance is one check of a lesson, with its name, points and parameters."""

    KIND: ClassVar[str] = ""
    SUMMARY: ClassVar[str] = ""
    PARAMS: ClassVar[tuple[Param, ...]] = ()
    PASSES_WITHOUT_MOVING: ClassVar[bool] = False  # a robot that never moves passes it: never a goal

    def __init__(
        self,
        name: str,
        points: float,
        values: dict[str, Any],
        nodes: dict[str, Node] | None = None,
        goal: bool = False,
        robot: str | None = None,
    ):
        self.name = name
        self.points = points
        self.goal = goal  # a goal check: the others count only once every goal check passes
        self.robot = robot  # the robot it looks at, by name (None: the student's)
        self.values = values
        self.nodes = nodes or {}  # where each parameter was written, for errors found later
        for key, value in values.items():
            setattr(self, key, value)

    def __repr__(self) -> str:
        goal = ", goal" if self.goal else ""
        robot = f", robot {self.robot}" if self.robot else ""
        return f"{type(self).__name__}({self.name!r}, {self.points:g} points{goal}{robot}, {self.values})"

    def passes_without_moving(self) -> bool:
        """Whether a robot that stands still where it starts passes this check (then it cannot be a goal)."""
        return self.PASSES_WITHOUT_MOVING

    def brief_of(self, outcome: Outcome) -> str:
        """The outcome's sentence without numbers, for hidden variants."""
        if outcome.brief:
            return outcome.brief
        return "passed" if outcome.passed else f"did not pass ({self.SUMMARY or self.KIND})"

    @classmethod
    def build(
        cls,
        name: str | None = None,
        points: float = 1,
        goal: bool = False,
        robot: str | None = None,
        **values: Any,
    ) -> Check:
        """A check made in code (tests, custom checks): parameters by keyword, defaults filled in."""
        known = {p.name: p for p in cls.PARAMS}
        for key in values:
            if key not in known:
                raise TypeError(f"{cls.KIND} has no parameter {key!r}; it has: {', '.join(known)}")
        full = {}
        for param in cls.PARAMS:
            if param.name in values:
                full[param.name] = values[param.name]
            elif param.required:
                raise TypeError(f"{cls.KIND} needs the parameter {param.name!r}")
            else:
                full[param.name] = param.default
        return cls(name or cls.KIND, points, full, goal=goal, robot=robot)

    def validate(self, world: World, variant: str) -> None:
        """Refuse parameters the world cannot answer (a region it does not have); called for every variant."""
        for param in self.PARAMS:
            if param.kind == "region":
                self.require_region(world, variant, param.name, getattr(self, param.name))

    def require_region(self, world: World, variant: str, param: str, region: str | None) -> None:
        """WorldFileError pointing at the parameter when `region` is not one of the world's regions."""
        if region is None or region in world.regions:
            return
        known = ", ".join(world.regions) or "none"
        message = (
            f"check '{self.name}': the world of variant '{variant}' ({world.source or world.name}) has no "
            f"region '{region}'; its regions: {known}"
        )
        node = self.nodes.get(param)
        if node is None:
            raise ValueError(message)
        raise node.error(message)

    def evaluate(self, run: RunRecord) -> Outcome:
        """Judge the run; see the class docstring of each kind."""
        raise NotImplementedError


CHECKS: dict[str, type[Check]] = {}
"""The built-in check kinds by YAML name (filled by the modules in `checks/`)."""


def register(cls: type[Check]) -> type[Check]:
    """Class decorator: make a check kind known by its KIND."""
    if not cls.KIND:
        raise ValueError(f"{cls.__name__} has no KIND")
    common = [p.name for p in cls.PARAMS if p.name in COMMON_KEYS]
    if common:
        raise ValueError(f"{cls.__name__} has a parameter named {common[0]!r}, a key of every check")
    if cls.KIND in CHECKS and CHECKS[cls.KIND] is not cls:
        raise ValueError(f"two check kinds named {cls.KIND!r}")
    CHECKS[cls.KIND] = cls
    return cls


def builtin_checks() -> dict[str, type[Check]]:
    """Every built-in check kind by name."""
    from . import checks  # noqa: F401 - registers the kinds

    return dict(CHECKS)


def check_from_node(node: Node, kinds: dict[str, type[Check]], index: int) -> Check:
    """One check from its YAML mapping (`kind`, `name`, `points` and the kind's parameters)."""
    example = "- {kind: reach_region, region: goal, goal: true, points: 5}"
    if not node.is_mapping:
        raise node.error(f"each check is a mapping like `{example}`, got {node.describe()}")
    fields = node.as_fields("check", None, example)
    kind_node = fields.require("kind", "kind: reach_region")
    kind = kind_node.as_text("kind", "kind: reach_region").strip()
    if kind not in kinds:
        close = difflib.get_close_matches(kind, list(kinds), n=1)
        hint = f"did you mean '{close[0]}'? " if close else ""
        raise kind_node.error(f"unknown check kind '{kind}'; {hint}known kinds: {', '.join(sorted(kinds))}")
    cls = kinds[kind]
    fields.check_keys(COMMON_KEYS + tuple(p.name for p in cls.PARAMS))
    name = fields.text("name", default=kind, example=f"name: {kind}").strip()
    if not name:
        raise fields.get("name").error("a check's name cannot be empty")
    points = fields.number("points", default=1.0, example="points: 2")
    if points < 0:
        raise fields.get("points").error(f"'points' cannot be negative, got {points:g}")
    goal = fields.boolean("goal", default=False)
    values: dict[str, Any] = {}
    nodes: dict[str, Node] = {}
    robot = None  # the student's
    if "robot" in fields:  # which robot of the run it looks at (checked against each variant's robots later)
        nodes["robot"] = fields.get("robot")
        robot = fields.text("robot", example="robot: pacer").strip() or None
    for param in cls.PARAMS:
        value_node = fields.get(param.name)
        if value_node is None or value_node.is_null:
            if param.required:
                raise node.error(
                    f"check '{name}' ({kind}) needs '{param.name}': {param.help}; add e.g. `{param.example()}`",
                    column=False,
                )
            values[param.name] = param.default
            continue
        values[param.name] = param.value_of(value_node)
        nodes[param.name] = value_node
    check = cls(name, points, values, nodes, goal=goal, robot=robot)
    if goal and robot not in (None, STUDENT):
        raise fields.get("goal").error(
            f"check '{name}' looks at the robot '{robot}', not the student's: it cannot be a goal, which is "
            "the student's task; leave it a secondary check"
        )
    if goal and check.passes_without_moving():
        raise fields.get("goal").error(
            f"check '{name}' ({kind}) passes for a robot that never moves, so it cannot be a goal: "
            "mark the check of the task itself (reaching a place, a distance, a lap ...) `goal: true`, "
            "and leave this one a secondary check that counts once the goal is met"
        )
    return check


def checks_from_node(node: Node, kinds: dict[str, type[Check]]) -> list[Check]:
    """The `checks:` list of a lesson; names must be unique, and at least one check must be a goal."""
    items = node.as_list("checks", "checks: [{kind: reach_region, region: goal, points: 5}]")
    if not items:
        raise node.error("a lesson needs at least one check; e.g. `- {kind: reach_region, region: goal}`")
    result: list[Check] = []
    seen: dict[str, Node] = {}
    for index, item in enumerate(items):
        check = check_from_node(item, kinds, index)
        if check.name in seen:
            raise item.error(
                f"two checks are named '{check.name}' (the first on line {seen[check.name].line}); "
                "give one of them another `name:`",
                column=False,
            )
        seen[check.name] = item
        result.append(check)
    if not any(check.goal for check in result):
        raise node.error(
            "no check is the lesson's goal: mark the check(s) of the task itself `goal: true`, e.g. "
            "`- {kind: reach_region, region: goal, goal: true, points: 5}`; the other checks (stopped, "
            "no wall contact, finished ...) count only once every goal check passes"
        )
    return result


__all__ = [
    "CHECKS",
    "Check",
    "Outcome",
    "POINT_PARAM",
    "Param",
    "REQUIRED",
    "WorldFileError",
    "builtin_checks",
    "check_from_node",
    "checks_from_node",
    "register",
]
