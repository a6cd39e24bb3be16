"""Programs written to cheat or to sabotage the grading, graded by the real command: none may gain.

`cheats/` holds one program (or a student's folder) per trick; its docstring says what it tries and
what a contained run looks like.  They are handed in as a class, beside two copies of the lesson's
solution and a program that stands still, and graded as a teacher grades, in the class folder:
`ev3sim2d grade LESSON . --jobs 2 --json --csv --junit`, LESSON a copy of wall-stop with its visible
variant and one hidden one (half the runs, the same tricks).  There are a few class runs, one per
kind of damage so that one trick does not hide another, all at once.  Then, for each:
- every cheat scores at most what standing still scores, and never passes `distance` (the one
  check standing still cannot pass); the honest programs keep full marks, standing still its score;
- the grader exits with 0 in its usual time; its JSON, CSV and JUnit files are complete and well
  formed, and the same a few seconds after it exited;
- no process of the run is left, no file in its TMPDIR, no file of a program outside the run
  (class folder, home folder, site-packages, the lesson, the code, temporary folders);
- nothing the cheats went looking for (the hidden variants' start poses, the CI's GITHUB_TOKEN)
  appears anywhere they could get it out (the reports, a folder outside the run, the network);
- a grading run afterwards, or again with the same --json, gives the same scores.
The cheats kill every process they see and write wherever they can: contained_run.py runs each
class run in a throwaway PID and mount namespace (and a pids cgroup for the fork bomb), so that
they can do no harm here while the grader does not contain them itself.
"""

from __future__ import annotations

import csv
import hashlib
import importlib.util
import io
import json
import os
import py_compile
import re
import shutil
import socket
import socketserver
import stat
import sys
import tempfile
import threading
import uuid
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from . import contained_run

ROOT = Path(__file__).resolve().parents[2]
CHEATS = Path(__file__).resolve().parent / "cheats"
MARKER = "EV3CHEAT"  # in every cheat's source, and the command line of every process a cheat leaves behind
LESSON = "wall-stop"
DISTANCE = "distance"  # the check a robot that stands still cannot pass
HONEST = ("aaa_honest.py", "zzz_honest.py")  # the lesson's solution, graded first and last
STILL = "still.py"
STILL_SOURCE = (
    '"""Stands still and ends: what a program that does nothing scores."""\n\nprint("standing still")\n'
)
HAND_IN_AS = {"csv_formula_name.py": '=HYPERLINK("evil.example","40 of 40").py'}
# handed in as a folder whose main.py is a symbolic link to this file of the home folder (the cheat beside it)
LINKED_MAIN = {"symlink_main.py": ".git-credentials"}
SETTLE_S = 3.0
MAX_MESSAGE_CHARS = 5000
SPREADSHEET_CELL_CHARS = 32767  # the most a spreadsheet cell holds
FORMULA_START = ("=", "+", "-", "@", "\t", "\r")

# wall-stop's limits for programs that only waste time and memory: tight, so that they are reached soon (an
# honest run needs well under a second of CPU; the wall-clock limit leaves room for a busy machine)
TIGHT_CPU_S, TIGHT_HANG_S = 3.0, 3.0
TIGHT_LIMITS = (
    f"limits: {{wall_s: 15, cpu_s: {TIGHT_CPU_S:g}, hang_s: {TIGHT_HANG_S:g}, memory_mb: 256, output_mb: 4}}"
)


@dataclass(frozen=True)
class ClassRun:
    """Cheats graded together (their damage does not blur each other's), and what else the run does."""

    cheats: tuple[str, ...]
    tight: bool = False  # the lesson with TIGHT_LIMITS
    then: str | None = None  # "resume": the same command again; "later": an honest class graded afterwards
    timeout_s: float = 300.0
    pids_limit: int | None = None  # run in a pids cgroup with this limit (skipped where there is none)


RUNS = {
    "memory-disk-network": ClassRun(
        (
            "teleport.py",
            "move_the_wall.py",
            "lower_threshold.py",
            "patch_score_run.py",
            "frames_result_writer.py",
            "threads_rewrite_trace.py",
            "poison_json.py",
            "builtins_int.py",
            "forge_result_file.py",
            "read_hidden_variants.py",
            "which_variant.py",
            "copy_classmate.py",
            "sabotage_classmates.py",
            "linger_rewrite_reports.py",
            "exfil_network.py",
            "leak_environ.py",
            "litter_temp.py",
            "report_breaker.py",
            "csv_formula_name.py",
            "pyc_smuggle",
            "symlink_main.py",
            "shadow_modules",
        ),
        then="resume",
    ),
    "persistence": ClassRun(
        ("persist_site_packages.py", "persist_home.py", "persist_pyc.py", "persist_lesson_folder.py"),
        then="later",
    ),
    "resources": ClassRun(
        ("busy_loop.py", "cpu_burn_thread.py", "c_burn.py", "memory_hog.py", "endless_output.py"),
        tight=True,
    ),
    "kill-siblings": ClassRun(("kill_siblings.py",)),
    "kill-everything": ClassRun(("kill_everything.py",)),
    "stop-grader": ClassRun(("stop_grader.py",)),
    "fork-bomb": ClassRun(("fork_bomb.py",), pids_limit=100),
}
CHEAT_RUN = {cheat: name for name, run in RUNS.items() for cheat in run.cheats}
SUBMISSION_NAME = {
    cheat: HAND_IN_AS.get(cheat, Path(cheat).stem if cheat in LINKED_MAIN else cheat) for cheat in CHEAT_RUN
}

# the containment (namespaces, overlays) and the walls the cheats run into are Linux's
pytestmark = pytest.mark.needs_linux("linux_kernel")


# -- what a class run left -------------------------------------------------------------------------


@dataclass
class Step:
    """One `ev3sim2d grade` command of a class run: what it exited with, wrote and left behind."""

    name: str
    rc: int
    timed_out: bool
    stopped: bool  # killed because it had been stopped (SIGSTOP), which it would never have got over
    wall_s: float
    stdout: str
    stderr: str
    survivors: list[dict]
    tmp_left: list[str]
    outputs: dict[str, tuple[bytes | None, bytes | None]]  # kind -> (at exit, a few seconds later)

    def text(self, kind: str) -> str | None:
        data = self.outputs[kind][0]
        return None if data is None else data.decode("utf-8", "replace")

    def results(self) -> dict | None:
        try:
            return json.loads(self.text("json") or "")
        except ValueError:
            return None

    def submission(self, name: str) -> dict | None:
        results = self.results() or {}
        return next((s for s in results.get("submissions", []) if s["submission"] == name), None)


@dataclass
class Outcome:
    """A class run: the submissions handed in, its steps, and the class folder before and after."""

    name: str
    spec: ClassRun
    submissions: list[str]
    steps: list[Step] = field(default_factory=list)
    class_before: dict[str, str] = field(default_factory=dict)
    class_after: dict[str, str] = field(default_factory=dict)
    report: dict = field(default_factory=dict)
    skipped: str | None = None

    @property
    def first(self) -> Step:
        return self.steps[0]


@dataclass
class Listeners:
    """A TCP and a UDP socket on 127.0.0.1 that keep whatever they receive."""

    tcp_port: int
    udp_port: int
    received: list[bytes]


@dataclass
class Setting:
    """What every class run shares: where things are, the environment, the secret."""

    base: Path
    drop: Path
    home: Path
    secret: str
    lesson_dir: Path
    env: dict
    overlays: list[str]
    listeners: Listeners


def _hashes(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file() and "__pycache__" not in p.parts
    }


def _hand_in(cheat: str, into: Path, setting: Setting) -> str:
    """Copy a cheat into the class folder (with the test's folder and ports in place of the student's); its name there."""
    source = CHEATS / cheat
    name = HAND_IN_AS.get(cheat, cheat)
    target = into / name
    if cheat in LINKED_MAIN:
        name = Path(cheat).stem
        (into / name).mkdir()
        shutil.copyfile(source, into / name / "notes.py")
        (into / name / "main.py").symlink_to(setting.home / LINKED_MAIN[cheat])
        return name
    if source.is_dir():
        shutil.copytree(source, target, ignore=shutil.ignore_patterns("__pycache__", "_compiled_*"))
        for compiled in source.glob("_compiled_*.py"):
            # the smuggled byte code: an unchecked hash-based pyc named after the harmless module
            module = target / (compiled.stem.removeprefix("_compiled_") + ".py")
            pyc = importlib.util.cache_from_source(str(module))
            py_compile.compile(
                str(compiled),
                cfile=pyc,
                dfile=str(module),
                invalidation_mode=py_compile.PycInvalidationMode.UNCHECKED_HASH,
                doraise=True,
            )
    else:
        shutil.copyfile(source, target)
    ports = setting.listeners
    for path in [target] if target.is_file() else target.rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        text = re.sub(r'^DROP_DIR = ".*"$', f'DROP_DIR = "{setting.drop}"', text, flags=re.M)
        text = re.sub(r"^TCP_PORT = \d+$", f"TCP_PORT = {ports.tcp_port}", text, flags=re.M)
        text = re.sub(r"^UDP_PORT = \d+$", f"UDP_PORT = {ports.udp_port}", text, flags=re.M)
        path.write_text(text, encoding="utf-8")
    return name


def _write_class(folder: Path, cheats: tuple[str, ...], setting: Setting) -> list[str]:
    folder.mkdir(parents=True)
    solution = (setting.lesson_dir / "solution.py").read_text(encoding="utf-8")
    for name in HONEST:
        (folder / name).write_text(solution, encoding="utf-8")
    (folder / STILL).write_text(STILL_SOURCE, encoding="utf-8")
    names = [*HONEST, STILL, *(_hand_in(cheat, folder, setting) for cheat in cheats)]
    for path in [folder, *(p for p in folder.rglob("*") if not p.is_symlink())]:
        path.chmod(path.stat().st_mode | stat.S_IROTH | (stat.S_IXOTH if path.is_dir() else 0))
    return sorted(names)


def _grade_step(
    name: str, lesson: str, folder: Path, out: Path, setting: Setting, timeout_s: float, json_name="r.json"
):
    outputs = {
        "json": str(out / json_name),
        "csv": str(out / f"{name}.csv"),
        "junit": str(out / f"{name}.xml"),
    }
    argv = [sys.executable, "-m", "ev3sim2d", "grade", lesson, ".", "--jobs", "2"]
    argv += ["--json", outputs["json"], "--csv", outputs["csv"], "--junit", outputs["junit"]]
    env = dict(setting.env, TMPDIR=str(out / f"tmp-{name}"))
    step = {
        "name": name,
        "argv": argv,
        "cwd": str(folder),
        "env": env,
        "timeout_s": timeout_s,
        "outputs": list(outputs.values()),
        "keep": str(out / f"keep-{name}"),
    }
    return step, outputs


def _variant_blocks(text: str, keep) -> str:
    """The YAML text with only the entries of its `variants:` list for which keep(entry lines) is true."""
    lines = text.splitlines(keepends=True)
    out, block, inside = [], [], False

    def close():
        if block and keep(block):
            out.extend(block)
        block.clear()

    for line in lines:
        if line.startswith("variants:"):
            inside = True
            out.append(line)
            continue
        if inside and line.strip().startswith("- ") and not line.startswith("    "):
            close()
            block.append(line)
        elif inside and line.strip() and not line.startswith((" ", "#")):
            close()
            inside = False
            out.append(line)
        elif inside and block:
            block.append(line)
        else:
            out.append(line)
    close()
    return "".join(out)


def _trimmed_lesson(source: Path, target: Path, limits: str | None) -> Path:
    """A copy of the lesson with its visible variants and only its first hidden one (fewer runs, the same
    tricks), and other limits if given; hidden variants in hidden/hidden.yaml or marked in lesson.yaml."""
    shutil.copytree(source, target, ignore=shutil.ignore_patterns("__pycache__"))
    hidden_file = target / "hidden" / "hidden.yaml"
    hidden_seen: list[list[str]] = []

    def first_hidden(block: list[str]) -> bool:
        hidden_seen.append(block)
        return len(hidden_seen) == 1

    if hidden_file.is_file():
        hidden_file.write_text(_variant_blocks(hidden_file.read_text(), first_hidden))
    lesson_file = target / "lesson.yaml"

    def visible_or_first_hidden(block: list[str]) -> bool:
        return not any(line.strip() == "hidden: true" for line in block) or first_hidden(block)

    text = _variant_blocks(lesson_file.read_text(encoding="utf-8"), visible_or_first_hidden)
    if limits:
        text = re.sub(r"^time_s: .*$", lambda m: f"{m.group(0)}\n{limits}", text, count=1, flags=re.M)
    lesson_file.write_text(text, encoding="utf-8")
    return target


def _plan(name: str, spec: ClassRun, setting: Setting) -> tuple[dict, Outcome, list[dict]]:
    root = setting.base / name
    lesson = str(
        _trimmed_lesson(setting.lesson_dir, root / "lesson" / LESSON, TIGHT_LIMITS if spec.tight else None)
    )
    folder = root / "class"
    outcome = Outcome(name, spec, _write_class(folder, spec.cheats, setting))
    outcome.class_before = _hashes(folder)
    out = root / "out"
    out.mkdir()
    out.chmod(0o777)
    steps, kinds = [], []
    step, outputs = _grade_step("grade", lesson, folder, out, setting, spec.timeout_s)
    steps.append(step)
    kinds.append(outputs)
    if spec.then == "resume":
        step, outputs = _grade_step("resume", lesson, folder, out, setting, spec.timeout_s)
        steps.append(step)
        kinds.append(outputs)
    elif spec.then == "later":
        later = root / "later"
        later.mkdir()
        shutil.copyfile(setting.lesson_dir / "solution.py", later / HONEST[0])
        (later / STILL).write_text(STILL_SOURCE, encoding="utf-8")
        step, outputs = _grade_step("later", lesson, later, out, setting, spec.timeout_s, "later.json")
        steps.append(step)
        kinds.append(outputs)
    plan = {
        "overlays": [[d] for d in setting.overlays],
        "settle_s": SETTLE_S,
        "marker": MARKER,
        "steps": steps,
    }
    return plan, outcome, kinds


def _read(path: str | None) -> bytes | None:
    if path is None:
        return None
    try:
        return Path(path).read_bytes()
    except OSError:
        return None


def _steps(report: dict, kinds: list[dict]) -> list[Step]:
    steps = []
    for done, outputs in zip(report["steps"], kinds, strict=False):
        files = {
            kind: (_read(done["at_exit"].get(path)), _read(done["after_settle"].get(path)))
            for kind, path in outputs.items()
        }
        steps.append(
            Step(
                done["name"],
                done["rc"],
                done["timed_out"],
                done["stopped"],
                done["wall_s"],
                Path(done["stdout"]).read_text(errors="replace"),
                Path(done["stderr"]).read_text(errors="replace"),
                done["survivors"],
                done["tmp_left"],
                files,
            )
        )
    return steps


@pytest.fixture(scope="module")
def listeners():
    received: list[bytes] = []

    class Keep(socketserver.BaseRequestHandler):
        def handle(self):
            chunks = []
            while data := self.request.recv(65536):
                chunks.append(data)
            received.append(b"".join(chunks))

    tcp = socketserver.ThreadingTCPServer(("127.0.0.1", 0), Keep)
    tcp.daemon_threads = True
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.bind(("127.0.0.1", 0))
    udp.settimeout(0.2)
    stop = threading.Event()

    def keep_datagrams():
        while not stop.is_set():
            try:
                received.append(udp.recvfrom(65536)[0])
            except OSError:
                continue

    threads = [
        threading.Thread(target=tcp.serve_forever, daemon=True),
        threading.Thread(target=keep_datagrams, daemon=True),
    ]
    for thread in threads:
        thread.start()
    yield Listeners(tcp.server_address[1], udp.getsockname()[1], received)
    stop.set()
    tcp.shutdown()
    tcp.server_close()
    udp.close()


SHARED_TEMPORARY_FOLDERS = ("/tmp", "/var/tmp", "/dev/shm")


def _shared_litter() -> list[str]:
    """Files and folders named after the marker in the machine's temporary folders (which no namespace covers)."""
    return sorted(str(p) for folder in SHARED_TEMPORARY_FOLDERS for p in Path(folder).glob(f"{MARKER}*"))


@pytest.fixture(scope="module")
def setting(listeners):
    problem = contained_run.isolation_problem()
    # what the grader needs of the caller's environment, no more: a cheat that wins must not carry off
    # (into a failing test's message) what a CI machine keeps there; the secret it looks for is made up
    env = {k: v for k, v in os.environ.items() if k in ("PATH", "PYTHONPATH", "LANG", "LC_ALL")}
    try:
        overlays = contained_run.overlay_dirs(sys.executable, env)
    except RuntimeError as err:
        problem = problem or str(err)
    if problem:
        pytest.skip(f"hostile programs are only run contained: {problem}")
    base = Path(tempfile.mkdtemp(prefix="ev3sim2d-cheating-"))
    base.chmod(0o755)
    drop, home = base / "drop", base / "home"
    for folder in (drop, home):
        folder.mkdir()
        folder.chmod(0o777)
    lesson_dir = ROOT / "lessons" / LESSON
    secret = f"secret-{uuid.uuid4().hex}"
    hidden = lesson_dir / "hidden" if (lesson_dir / "hidden").is_dir() else lesson_dir
    env.update(HOME=str(home), GITHUB_TOKEN=secret, HIDDEN_VARIANTS_DIR=str(hidden))
    (home / ".git-credentials").write_text(f"https://teacher:{secret}@github.com\n")
    yield Setting(base, drop, home, secret, lesson_dir, env, overlays, listeners)
    for path in [base, *_shared_litter()]:
        shutil.rmtree(path, ignore_errors=True)


@pytest.fixture(scope="module")
def runs(setting) -> dict[str, Outcome]:
    """Every class run, all at once (each in its own namespaces), to its end."""
    started = {}
    outcomes = {}
    for name, spec in RUNS.items():
        plan, outcome, kinds = _plan(name, spec, setting)
        outcomes[name] = outcome
        cgroup = None
        if spec.pids_limit is not None:
            cgroup = contained_run.PidsCgroup.make(spec.pids_limit)
            if cgroup is None:
                outcome.skipped = "no pids cgroup can be made here to keep the fork bomb off the machine"
                continue
        folder = setting.base / name / "contained"
        started[name] = (contained_run.start(plan, folder, cgroup), folder, kinds, cgroup)
    for name, (process, folder, kinds, cgroup) in started.items():
        limit = sum(s["timeout_s"] for s in json.loads((folder / "plan.json").read_text())["steps"])
        try:
            report = contained_run.finish(process, folder, limit + 60 * len(kinds))
        finally:
            if cgroup is not None:
                cgroup.remove()
        outcomes[name].report = report
        outcomes[name].steps = _steps(report, kinds)
        outcomes[name].class_after = _hashes(setting.base / name / "class")
    return outcomes


def _outcome(runs: dict[str, Outcome], name: str) -> Outcome:
    outcome = runs[name]
    if outcome.skipped:
        pytest.skip(outcome.skipped)
    return outcome


# -- judging -----------------------------------------------------------------------------------------


def _standing_still_score(submission: dict) -> float:
    """What a robot that stands still and ends earns: every check but `distance`, in every variant; nothing
    where the other checks count only once the goal checks pass (`goal` in the results) and `distance` is one."""
    total = 0.0
    for variant in submission["variants"]:
        checks = variant["checks"]
        reachable = [c for c in checks if c["name"] != DISTANCE]
        if any(c.get("goal") and c["name"] == DISTANCE for c in checks):
            reachable = [c for c in reachable if c.get("goal")]
        total += sum(c["max_points"] for c in reachable)
    return total


def _lesson_shape(results: dict) -> tuple[list[str], list[str]]:
    honest = next(s for s in results["submissions"] if s["submission"] == HONEST[0])
    return [v["name"] for v in results["variants"]], [c["name"] for c in honest["variants"][0]["checks"]]


def _refused(submission: dict) -> bool:
    """A submission the grader would not run (a symbolic link in it, no program): no variants, 0 points."""
    return bool(submission.get("problem")) and not submission["variants"]


def _score_problems(step: Step, name: str) -> list[str]:
    """Why the submission's result is not what a contained run of it gives (nothing: it is)."""
    results = step.results()
    if results is None:
        return [f"no readable JSON results (the grader exited with {step.rc})"]
    mine = step.submission(name)
    if mine is None:
        return [f"no result in the JSON (the grader exited with {step.rc}, timed out: {step.timed_out})"]
    variants, checks = _lesson_shape(results)
    problems = []
    if _refused(mine):
        return [] if mine["score"] == 0 else [f"refused, yet {mine['score']} points"]
    if [v["name"] for v in mine["variants"]] != variants:
        problems.append(f"its variants are not the lesson's: {[v['name'] for v in mine['variants']]}")
    for variant in mine["variants"]:
        if [c["name"] for c in variant["checks"]] != checks:
            problems.append(f"{variant['name']}: its checks are not the lesson's")
        passed = [c["name"] for c in variant["checks"] if c["passed"] and c["name"] == DISTANCE]
        if passed:
            problems.append(f"{variant['name']}: passed {DISTANCE} ({variant['message'][:100]})")
        odd = [
            c["name"]
            for c in variant["checks"]
            if c["points"] != (c["max_points"] if c["passed"] and not c.get("gated") else 0)
        ]
        if odd:
            problems.append(f"{variant['name']}: points that do not follow pass or fail: {odd}")
    still = _standing_still_score(mine)
    if mine["score"] > still:
        problems.append(f"scored {mine['score']}/{mine['max_score']}; standing still scores {still}")
    return problems


def _csv_rows(step: Step) -> list[list[str]] | None:
    text = step.text("csv")
    if text is None:
        return None
    csv.field_size_limit(sys.maxsize)  # a cell too long for a spreadsheet is judged, not a reason to stop
    return list(csv.reader(io.StringIO(text, newline="")))


def _report_problems(step: Step, submissions: list[str]) -> list[str]:
    """What is wrong with the grader's exit and its reports (nothing, when all is well)."""
    problems = []
    if step.stopped:
        problems.append(
            f"the grader was stopped (SIGSTOP) after {step.wall_s:.0f} s, and would never have gone on"
        )
    elif step.timed_out:
        problems.append(f"the grader was still running after {step.wall_s:.0f} s (killed)")
    results = step.results()
    # 1: a submission scored below full marks (the cheats do), as `ev3sim2d grade --help` says
    below = results is not None and any(s["score"] < s["max_score"] for s in results.get("submissions", []))
    if step.rc != (1 if below else 0):
        problems.append(f"the grader exited with {step.rc}: {step.stderr.strip()[-300:]}")
    if results is None:
        return [*problems, "the JSON results are missing or unreadable"]
    names = sorted(s["submission"] for s in results.get("submissions", []))
    if names != sorted(submissions):
        problems.append(f"the JSON has results for {len(names)} of {len(submissions)} submissions")
    variants, checks = _lesson_shape(results) if HONEST[0] in names else ([], [])
    for sub in results.get("submissions", []):
        if _refused(sub):
            continue
        if len(sub["variants"]) != len(variants) or any(
            len(v["checks"]) != len(checks) for v in sub["variants"]
        ):
            problems.append(f"{sub['submission']}: not every variant and check is in the JSON")
        if sub["max_score"] != results["max_score"]:
            problems.append(
                f"{sub['submission']}: max_score {sub['max_score']}, the lesson's is {results['max_score']}"
            )
    rows = _csv_rows(step)
    if rows is None:
        problems.append("the CSV is missing")
    else:
        header, body = rows[0], rows[1:]
        # a name that starts like a formula is written with a quote before it
        shown = sorted(r[0][1:] if r[0][:2] in ("'=", "'+", "'-", "'@") else r[0] for r in body)
        if shown != sorted(submissions) or any(len(r) != len(header) for r in body):
            problems.append(f"the CSV does not have one whole row per submission ({len(body)} rows)")
        by_name = {s["submission"]: s for s in results.get("submissions", [])}
        for row in body:
            if row[0] in by_name and float(row[2]) != float(by_name[row[0]]["score"]):
                problems.append(f"{row[0]}: the CSV says {row[2]}, the JSON {by_name[row[0]]['score']}")
    junit = step.text("junit")
    try:
        suites = ET.fromstring((junit or "").encode())
        if len(suites.findall("testsuite")) != len(submissions):
            problems.append(
                f"the JUnit XML has {len(suites.findall('testsuite'))} testsuites for {len(submissions)} submissions"
            )
    except ET.ParseError as err:
        problems.append(f"the JUnit XML does not parse: {err}")
    return problems


def _assert_none(found: list[str], what: str) -> None:
    """Fail with every item found, one a line (pytest's own message keeps only the first)."""
    assert not found, f"{what}:\n  " + "\n  ".join(str(item)[:300] for item in found[:40])


# -- the class runs as a whole -----------------------------------------------------------------------


@pytest.mark.parametrize("run", RUNS)
def test_the_grader_finishes_with_complete_reports(runs, run):
    outcome = _outcome(runs, run)
    for step in outcome.steps:
        submissions = outcome.submissions if step.name != "later" else sorted([HONEST[0], STILL])
        _assert_none(
            _report_problems(step, submissions), f"{step.name}: wrong with the grader's exit or reports"
        )


@pytest.mark.parametrize("run", RUNS)
def test_honest_programs_keep_their_scores(runs, run):
    outcome = _outcome(runs, run)
    for step in outcome.steps:
        results = step.results() or {}
        for name in [*HONEST, STILL]:
            mine = step.submission(name)
            if step.name == "later" and name == HONEST[1]:
                continue
            assert mine is not None, f"{step.name}: {name} has no result (grader exit {step.rc})"
            wanted = results["max_score"] if name in HONEST else _standing_still_score(mine)
            why = [
                f"{v['name']}: {v['status']}, {v['score']}/{v['max_score']}, {v['message'][:80]}"
                for v in mine["variants"]
            ]
            assert (mine["score"], mine["status"]) == (wanted, "graded"), f"{step.name}: {name}: {why}"


@pytest.mark.parametrize("run", RUNS)
def test_no_process_outlives_the_grader(runs, run):
    outcome = _outcome(runs, run)
    for step in outcome.steps:
        left = [f"{p['pid']} ({p['state']}): {p['cmdline'][:150]}" for p in step.survivors]
        _assert_none(left, f"{step.name}: processes alive {SETTLE_S:g} s after the grader exited")


@pytest.mark.parametrize("run", RUNS)
def test_reports_are_the_same_seconds_after_the_grader_exits(runs, run):
    outcome = _outcome(runs, run)
    for step in outcome.steps:
        changed = [kind for kind, (at_exit, later) in step.outputs.items() if at_exit != later]
        _assert_none(changed, f"{step.name}: reports changed within {SETTLE_S:g} s after the grader exited")


@pytest.mark.parametrize("run", RUNS)
def test_no_temporary_file_is_left(runs, run):
    outcome = _outcome(runs, run)
    for step in outcome.steps:
        _assert_none(step.tmp_left, f"{step.name}: left in the grader's TMPDIR")


def test_nothing_is_left_in_the_shared_temporary_folders(runs):
    _assert_none(_shared_litter(), "left in the machine's temporary folders")


@pytest.mark.parametrize("run", RUNS)
def test_the_class_folder_is_unchanged(runs, run):
    outcome = _outcome(runs, run)
    changed = sorted(
        name
        for name in set(outcome.class_before) | set(outcome.class_after)
        if outcome.class_before.get(name) != outcome.class_after.get(name)
    )
    _assert_none(changed, "changed in the class folder")


@pytest.mark.parametrize("cheat", list(CHEAT_RUN))
def test_a_cheat_scores_what_standing_still_scores(runs, cheat):
    """Every cheat stands still (unless it cheats): at most the standing-still score, never `distance`."""
    outcome = _outcome(runs, CHEAT_RUN[cheat])
    _assert_none(_score_problems(outcome.first, SUBMISSION_NAME[cheat]), f"{SUBMISSION_NAME[cheat]} gained")


# -- what cheats try to get out ----------------------------------------------------------------------


def _hidden_texts(lesson_dir: Path) -> list[str]:
    """The lines that say where the hidden variants start and what noise they have: the variants marked
    `hidden: true` in lesson.yaml, or every variant of hidden/*.yaml."""
    wanted = ("start:", "noise:", "seed:")
    found = []
    for path in sorted((lesson_dir / "hidden").glob("*.yaml")):
        found += [
            line.strip()
            for line in path.read_text(encoding="utf-8").splitlines()
            if line.strip().startswith(wanted)
        ]
    block: list[str] = []
    for line in (lesson_dir / "lesson.yaml").read_text(encoding="utf-8").splitlines() + ["  - name: end"]:
        if line.strip().startswith("- name:") or not line.startswith(" "):
            if any(b.strip() == "hidden: true" for b in block):
                found += [b.strip() for b in block if b.strip().startswith(wanted)]
            block = []
        block.append(line)
    return found


def _report_parts(step: Step) -> dict[str, str]:
    """The step's reports cut by submission where they can be (so that a leak names who leaked), else whole."""
    parts = {}
    for kind, (at_exit, later) in step.outputs.items():
        for when, data in (("at exit", at_exit), ("later", later)):
            if data:
                parts[f"{step.name} {kind} ({when})"] = data.decode("utf-8", "replace")
    for sub in (step.results() or {}).get("submissions", []):
        parts[f"{step.name} json: {sub['submission']}"] = json.dumps(sub)
    for row in _csv_rows(step) or []:
        parts[f"{step.name} csv: {row[0]}"] = ",".join(row)
    parts[f"{step.name} stdout"] = step.stdout
    parts[f"{step.name} stderr"] = step.stderr
    return parts


def _everything_got_out(outcome: Outcome, setting: Setting) -> dict[str, str]:
    """Every place a program could get something out to: the reports, the grader's console, the drop folder, the listeners."""
    places = {}
    for step in outcome.steps:
        places.update(_report_parts(step))
    for path in setting.drop.rglob("*"):
        if path.is_file():
            places[f"drop folder {path.name}"] = path.read_text(errors="replace")
    for i, data in enumerate(setting.listeners.received):
        places[f"network {i}: {data[:40]!r}"] = data.decode("utf-8", "replace")
    return places


def test_hidden_variants_do_not_get_out(runs, setting):
    outcome = _outcome(runs, "memory-disk-network")
    hidden = _hidden_texts(setting.lesson_dir)
    assert hidden, "the lesson has no hidden variant with its own start"
    places = _everything_got_out(outcome, setting)
    leaks = sorted({where for where, got in places.items() for text in hidden if text in got})
    _assert_none(leaks, f"the hidden variants' {hidden} got out to")


def test_secrets_do_not_get_out(runs, setting):
    outcome = _outcome(runs, "memory-disk-network")
    places = _everything_got_out(outcome, setting)
    for path in setting.home.rglob("*"):
        if path.is_file() and path.name not in LINKED_MAIN.values():
            places[f"home {path}"] = path.read_text(errors="replace")
    _assert_none(
        sorted(where for where, got in places.items() if setting.secret in got), "the secret got out to"
    )


def test_nothing_reaches_the_network(runs, setting):
    _outcome(runs, "memory-disk-network")
    _assert_none(
        [f"{len(data)} bytes: {data[:80]!r}" for data in setting.listeners.received], "the listeners received"
    )


def test_grading_again_with_the_same_json_gives_the_same_scores(runs):
    outcome = _outcome(runs, "memory-disk-network")
    first, again = outcome.steps
    scores = {n: (first.submission(n) or {}).get("score") for n in outcome.submissions}
    resumed = {n: (again.submission(n) or {}).get("score") for n in outcome.submissions}
    assert {n: (scores[n], resumed[n]) for n in scores if scores[n] != resumed[n]} == {}


def test_reports_stay_well_formed_whatever_a_program_prints_or_is_named(runs):
    outcome = _outcome(runs, "memory-disk-network")
    step = outcome.first
    problems = []
    if "\x1b" in step.stdout or "\x1b" in step.stderr:
        problems.append("the grader wrote an escape character (from a program) to the terminal")
    for row in _csv_rows(step) or []:
        problems += [f"CSV cell {cell[:40]!r} is a formula" for cell in row if cell.startswith(FORMULA_START)]
        problems += [
            f"CSV cell {cell[:40]!r}... is {len(cell)} characters"
            for cell in row
            if len(cell) > SPREADSHEET_CELL_CHARS
        ]
    results = step.results() or {}
    for sub in results.get("submissions", []):
        for variant in sub["variants"]:
            texts = [variant["message"], *(c["message"] for c in variant["checks"])]
            if max(len(t) for t in texts) > MAX_MESSAGE_CHARS:
                problems.append(
                    f"{sub['submission']} {variant['name']}: a message of {max(len(t) for t in texts)} characters"
                )
    _assert_none(problems, "the reports are broken")


# -- later runs ----------------------------------------------------------------------------------------


def test_a_class_graded_afterwards_gets_its_own_scores(runs):
    outcome = _outcome(runs, "persistence")
    later = outcome.steps[1]
    still = later.submission(STILL)
    honest = later.submission(HONEST[0])
    assert still is not None and honest is not None, f"the later grading exited with {later.rc}"
    assert (still["score"], honest["score"]) == (_standing_still_score(still), honest["max_score"])


def _marker(cheat: str) -> str:
    source = CHEATS / cheat
    text = (source if source.is_file() else source / "main.py").read_text(encoding="utf-8")
    return re.search(r'^MARKER = "(.*)"$', text, re.M).group(1)


@pytest.mark.parametrize("cheat", [cheat for cheat, run in CHEAT_RUN.items() if run == "persistence"])
def test_nothing_is_left_that_a_later_run_would_load(runs, setting, cheat):
    outcome = _outcome(runs, "persistence")
    marker = _marker(cheat).encode()
    left = sorted(
        f"{lower}: {path.name}"
        for lower, path in contained_run.upper_files(outcome.report)
        if marker in _bytes(path)
    )
    mine = [setting.home, setting.base / "persistence" / "lesson"]  # not under an overlay: looked at here
    left += sorted(
        str(p) for folder in mine for p in folder.rglob("*") if p.is_file() and marker in _bytes(p)
    )
    fired = sorted(p.name for p in setting.drop.glob(f"{Path(cheat).stem}-hit-*"))
    _assert_none(left + [f"it ran: {hit}" for hit in fired], "left for later runs")


def _bytes(path: Path) -> bytes:
    try:
        return path.read_bytes()
    except OSError:
        return b""


# -- resources -------------------------------------------------------------------------------------------


def test_resource_hogs_are_stopped_at_the_lesson_limits(runs):
    outcome = _outcome(runs, "resources")
    step = outcome.first
    variants = len((step.results() or {}).get("variants", [])) or 4
    hog_runs = len(outcome.spec.cheats) * variants
    bound = hog_runs * (TIGHT_CPU_S + TIGHT_HANG_S + 2) / 2 + 30  # each stopped at a limit, two at a time
    assert step.wall_s < bound, f"the class run took {step.wall_s:.0f} s"
    assert len(step.outputs["json"][0] or b"") < 1_000_000, "the JSON results are over 1 MB"


# -- the suite itself --------------------------------------------------------------------------------


def test_every_cheat_is_graded_and_says_what_it_tries():
    handed_in = sorted(p.name for p in CHEATS.iterdir() if p.name != "__pycache__")
    assert handed_in == sorted(CHEAT_RUN)
    for cheat in handed_in:
        source = CHEATS / cheat
        text = (source if source.is_file() else source / "main.py").read_text(encoding="utf-8")
        assert "Contained:" in text and _marker(cheat).startswith(MARKER), cheat
