"""Grading results as plain data: per check, per variant, per submission; to and from JSON.

Statuses of a variant and a submission:
- `graded`: the program ran to its end or to the time limit; the checks say the rest;
- `error`: the program raised an exception (or could not be started: a syntax error);
- `timeout`: it got stuck (a loop that never uses the robot or the clock) or ran past the wall/CPU limit;
- `memory`: it ran out of the memory it may use;
- `output`: it wrote more to the console than it may;
- `crashed`: the Python interpreter running it died (a segmentation fault, a signal);
- `missing`: no program to run was found.
A submission's status is the worst of its variants' (in the order crashed, memory, output, timeout, error, missing).

In a lesson with several robots each check's result names the robot it looked at (`robot`).
A secondary check that passed but earned nothing because a goal check of its variant failed is `gated`
(and not passed).

A hidden variant's result is named "hidden variant N" and tells its score, its status, whether each check
passed, and in words only what cannot carry more than that: how the run ended, one of HIDDEN_RUN (never the
program's exception, message, exit code, printed text, or a time), and for each check one sentence for a
pass and one for a fail (scoring.py).  A program could otherwise spell out what it senses of a hidden
world in what it chooses to raise, print or take.  A VariantResult made for a hidden variant (by scoring,
or read back from a results file) is sealed so: no times, no output, and its run's words one of HIDDEN_RUN.

What the student's program printed in a visible variant is kept (`output`), trimmed to the first
OUTPUT_HEAD and the last OUTPUT_TAIL lines, each cut at OUTPUT_LINE_CHARS characters; when anything was
left out `output_trimmed` is true and `output_lines_dropped` says how many lines.  A hidden variant keeps
none of it (`output` is null): a program could print what it senses of the hidden world.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

STATUS_ORDER = ("crashed", "memory", "output", "timeout", "error", "missing", "graded")
# All a hidden variant's result may say of its run, by how it ended.
HIDDEN_RUN = {
    "finished": "the program finished",
    "time_limit": "the program ran until the time limit",
    "error": "the program stopped with an error",
    "hung": "the program got stuck, so it was stopped",
    "timeout": "the program ran too long, so it was stopped",
    "memory": "the program ran out of memory",
    "output": "the program wrote too much to the console, so it was stopped",
    "crashed": "the run crashed",
    "not_started": "the program could not be started",
}
HIDDEN_RUN_OF_STATUS = {  # a variant's status -> the words a sealed hidden result falls back to
    "graded": "finished",
    "error": "error",
    "timeout": "timeout",
    "memory": "memory",
    "output": "output",
    "crashed": "crashed",
    "missing": "not_started",
}
OUTPUT_HEAD = 100  # printed lines kept from the start of a run
OUTPUT_TAIL = 100  # and from its end
OUTPUT_LINE_CHARS = 300  # a longer line is cut, and ends with "…"


@dataclass
class CheckResult:
    """One check in one variant."""

    name: str
    kind: str
    passed: bool
    points: float  # what it earned
    max_points: float
    message: str
    t_s: float | None = None
    goal: bool = False  # one of the lesson's goal checks
    gated: bool = False  # a secondary check that passed, but earned nothing because a goal check failed
    robot: str | None = None  # in a lesson with several robots, the one it looked at ("student", "pacer")


@dataclass
class VariantResult:
    """One submission in one variant: how the run went and what each check found."""

    name: str
    hidden: bool
    status: str
    message: str  # how the run ended, one line
    sim_time_s: float | None
    checks: list[CheckResult] = field(default_factory=list)
    # what the student's program printed, "12.50 s  text" a line (stderr lines: "12.50 s! text");
    # None in a hidden variant, or when the run left no record of it
    output: list[str] | None = None
    output_trimmed: bool = False
    output_lines_dropped: int = 0

    def __post_init__(self) -> None:
        if self.hidden:  # sealed: see the module docstring
            self.sim_time_s, self.output = None, None
            self.output_trimmed, self.output_lines_dropped = False, 0
            if self.message not in HIDDEN_RUN.values():
                self.message = HIDDEN_RUN[HIDDEN_RUN_OF_STATUS.get(self.status, "crashed")]
            for check in self.checks:
                check.t_s = None

    @property
    def score(self) -> float:
        return sum(c.points for c in self.checks)

    @property
    def max_score(self) -> float:
        return sum(c.max_points for c in self.checks)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.checks)

    def failed_checks(self) -> list[CheckResult]:
        """The checks that earned nothing: those that failed on their own first, then the gated ones."""
        failed = [c for c in self.checks if not c.passed]
        return [c for c in failed if not c.gated] + [c for c in failed if c.gated]

    def to_dict(self) -> dict:
        data = asdict(self)
        data["score"] = _number(self.score)
        data["max_score"] = _number(self.max_score)
        for check in data["checks"]:
            if check["robot"] is None:  # a lesson of one robot: the results read as they always did
                del check["robot"]
            check["points"] = _number(check["points"])
            check["max_points"] = _number(check["max_points"])
        return data

    @classmethod
    def from_dict(cls, data: dict) -> VariantResult:
        checks = [CheckResult(**c) for c in data.get("checks", [])]
        keys = ("name", "hidden", "status", "message", "sim_time_s", "output")
        return cls(
            **{k: data.get(k) for k in keys},
            checks=checks,
            output_trimmed=bool(data.get("output_trimmed", False)),
            output_lines_dropped=int(data.get("output_lines_dropped", 0)),
        )


def printed_output(lines, robot: int, dropped_before: int = 0) -> tuple[list[str], bool, int]:
    """A run's printed lines (`OutputLine`s) of one robot, trimmed as the module docstring says: the lines
    kept, whether any were left out, and how many (`dropped_before`: lines the run itself did not keep)."""
    own = [line for line in lines if line.robot == robot]
    kept = own if len(own) <= OUTPUT_HEAD + OUTPUT_TAIL else own[:OUTPUT_HEAD] + own[-OUTPUT_TAIL:]
    dropped = len(own) - len(kept) + dropped_before
    text = []
    cut = False
    for line in kept:
        words = line.text.rstrip("\n")
        if len(words) > OUTPUT_LINE_CHARS:
            words, cut = words[: OUTPUT_LINE_CHARS - 1] + "…", True
        mark = "!" if line.stream == "stderr" else " "
        text.append(f"{line.t_s:.2f} s{mark} {words}")
    return text, cut or dropped > 0, dropped


@dataclass
class SubmissionResult:
    """A submission graded in every variant of a lesson."""

    submission: str
    key: str
    variants: list[VariantResult] = field(default_factory=list)
    problem: str | None = None  # set when there was nothing to run, or the program could not be started
    max_points: float = 0.0  # used when there are no variant results (nothing to run)
    problem_status: str = "missing"  # the status a problem gives: missing, or error (a syntax error)

    @property
    def score(self) -> float:
        return sum(v.score for v in self.variants)

    @property
    def max_score(self) -> float:
        return sum(v.max_score for v in self.variants) if self.variants else self.max_points

    @property
    def status(self) -> str:
        if self.problem is not None:
            return self.problem_status
        statuses = {v.status for v in self.variants}
        return next((s for s in STATUS_ORDER if s in statuses), "graded")

    @property
    def full_marks(self) -> bool:
        return self.max_score > 0 and abs(self.score - self.max_score) < 1e-9

    def first_failure(self) -> str:
        """The first thing that went wrong, as one line for the table."""
        line = ""
        if self.problem:
            line = self.problem.splitlines()[0]  # a syntax error's first line: where, and what
        else:
            for variant in self.variants:
                failed = variant.failed_checks()
                if variant.hidden and (variant.status != "graded" or failed):
                    reason = variant.message if variant.status != "graded" else failed[0].message
                    line = f"{variant.name}: failed — {reason}"
                elif variant.status != "graded":
                    line = f"{variant.name}: {variant.message}"
                elif failed:
                    line = f"{variant.name}: {failed[0].name}: {failed[0].message}"
                if line:
                    break
        return " ".join(line.split())

    def to_dict(self) -> dict:
        return {
            "submission": self.submission,
            "key": self.key,
            "score": _number(self.score),
            "max_score": _number(self.max_score),
            "status": self.status,
            "problem": self.problem,
            "variants": [v.to_dict() for v in self.variants],
        }

    @classmethod
    def from_dict(cls, data: dict) -> SubmissionResult:
        return cls(
            submission=data["submission"],
            key=data.get("key", ""),
            variants=[VariantResult.from_dict(v) for v in data.get("variants", [])],
            problem=data.get("problem"),
            max_points=float(data.get("max_score", 0.0)),
            problem_status=data.get("status", "missing") if data.get("problem") is not None else "missing",
        )


def _number(value: float) -> float | int:
    """Whole numbers as ints in JSON (5, not 5.0)."""
    return int(value) if float(value).is_integer() else round(float(value), 3)
