#!/usr/bin/env python3
"""How long grading a class takes: thirty submissions of `line-follow` (or of a lesson of two robots).

The class is made up: thirty line followers as students write them, each with its own speed
and steering (most follow the line; some are too fast or too slow, one never starts), each in a
student's folder or as a single file.  They are graded with the command a teacher types:

    ev3sim2d grade line-follow CLASS --json results.json

(as many runs at a time as the grader chooses: grading/grader.py, default_jobs; --jobs N to say).
Target: under 30 s of wall time on a 2-core machine.  The same class is then graded by the code of
commit IN_PROCESS_COMMIT (taken from git), the last that ran programs inside the simulator's
process, for the ratio in one run (that lesson had fewer variants, so the ratio is per run).
--lesson convoy grades thirty copies of that lesson's own solution instead (its runs have two robots:
the student's and the pacer; no baseline, which had no such lessons).  --compare-jobs N also grades the
same class with --jobs N, for the ratio in one run.
Run:  python benchmarks/grade.py [--jobs N] [--students 30] [--lesson line-follow|convoy]
      [--compare-jobs N] [--keep DIR] [--no-baseline]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from old_code import IN_PROCESS_COMMIT, old_code

ROOT = Path(__file__).resolve().parents[1]

# run `python -m ev3sim2d` from the old code on PYTHONPATH, not today's editable install
OLD_MAIN = (
    "import sys, runpy; "
    "sys.meta_path = [f for f in sys.meta_path if not type(f).__module__.startswith('__editable__')]; "
    "runpy.run_module('ev3sim2d', run_name='__main__')"
)

FOLLOWER = """\
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
from ev3dev2.sensor import INPUT_3
from ev3dev2.sensor.lego import ColorSensor

SPEED = {speed}
GAIN = {gain}

tank = MoveTank(OUTPUT_B, OUTPUT_C)
eye = ColorSensor(INPUT_3)
while True:
    turn = GAIN * (eye.reflected_light_intensity - {edge})
    left = max(-100, min(100, SPEED + turn))
    right = max(-100, min(100, SPEED - turn))
    tank.on(SpeedPercent(left), SpeedPercent(right))
"""


def make_class(folder: Path, students: int) -> None:
    """`students` submissions: single files and students' folders (main.py and a module)."""
    for i in range(students):
        speed = 15 + (i * 7) % 50  # 15 .. 64 %
        gain = 0.3 + (i % 5) * 0.15
        edge = 35 + (i % 3) * 5
        source = FOLLOWER.format(speed=speed, gain=round(gain, 2), edge=edge)
        if i == students - 1:
            source = "print('I forgot to write the program')\n"
        if i % 3 == 0:
            student = folder / f"student{i:02d}"
            student.mkdir()
            (student / "settings.py").write_text(f"NAME = 'student {i}'\n")
            (student / "main.py").write_text("import settings  # noqa: F401\n" + source)
        else:
            (folder / f"student{i:02d}.py").write_text(source)


def grade_class(
    folder: Path, results: Path, jobs: int | None, code: Path | None = None, lesson: str = "line-follow"
) -> tuple[float, float, dict]:
    """Grade the class with `ev3sim2d grade` (jobs None: as the grader chooses); code: an old source tree
    to run instead of today's.  Returns the wall time, the CPU time of the grader and its workers, and the
    results document."""
    results.unlink(missing_ok=True)
    told = [] if jobs is None else ["--jobs", str(jobs)]
    args = ["grade", lesson, str(folder), *told, "--json", str(results), "--quiet"]
    env = {**os.environ, "PYTHONHASHSEED": "0"}
    if code is None:
        command, cwd = [sys.executable, "-m", "ev3sim2d", *args], None
    else:
        command, cwd = [sys.executable, "-c", OLD_MAIN, *args], code
        env["PYTHONPATH"] = str(code)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, cwd=cwd, env=env)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if done.returncode not in (0, 1) or not results.is_file():  # (1: some student scored less: graded)
        raise RuntimeError(f"grading failed:\n{done.stdout}\n{done.stderr}")
    return wall, cpu, json.loads(results.read_text())


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument(
        "--jobs", type=int, default=None, help="runs at a time (default: the grader's choice)"
    )
    parser.add_argument("--students", type=int, default=30)
    parser.add_argument("--lesson", choices=["line-follow", "convoy"], default="line-follow")
    parser.add_argument("--compare-jobs", type=int, metavar="N", help="also grade the class with --jobs N")
    parser.add_argument("--keep", metavar="DIR", help="make the class in DIR and keep it (and results.json)")
    parser.add_argument("--no-baseline", action="store_true", help="do not grade the class with the old code")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        root = Path(args.keep or scratch)
        folder = root / "class"
        folder.mkdir(parents=True, exist_ok=True)
        if args.lesson == "line-follow":
            make_class(folder, args.students)
        else:
            solution = (ROOT / "lessons" / args.lesson / "solution.py").read_text()
            for i in range(args.students):
                (folder / f"student{i:02d}.py").write_text(solution)
        told = "the grader's choice of runs at a time" if args.jobs is None else f"--jobs {args.jobs}"
        try:
            wall, cpu, data = grade_class(folder, root / "results.json", args.jobs, lesson=args.lesson)
        except RuntimeError as err:
            print(err, file=sys.stderr)
            return 1
        submissions = data["submissions"]
        runs = sum(len(s["variants"]) for s in submissions)
        full = sum(1 for s in submissions if s["score"] == s["max_score"])
        statuses = sorted({s["status"] for s in submissions})
        print(
            f"graded {len(submissions)} submissions of {args.lesson} ({runs} runs, {len(data['variants'])} "
            f"variants each) with {told} in {wall:.1f} s wall ({full} with full marks; statuses: "
            f"{', '.join(statuses)})"
        )
        print(f"CPU time of the grader and its workers: {cpu:.1f} s")
        if args.students == 30 and args.lesson == "line-follow":
            print(f"target: under 30 s -> {'met' if wall < 30 else 'NOT met'}")
        if args.compare_jobs is not None:
            other_wall, other_cpu, _ = grade_class(
                folder, root / "compared.json", args.compare_jobs, lesson=args.lesson
            )
            print(
                f"the same class with --jobs {args.compare_jobs}: {other_wall:.1f} s wall, {other_cpu:.1f} s CPU "
                f"(wall: {wall / other_wall:.2f} of it)"
            )
        code = None if args.no_baseline or args.lesson != "line-follow" else old_code(Path(scratch))
        if code is not None:
            try:
                old_wall, old_cpu, old = grade_class(folder, Path(scratch) / "old.json", args.jobs, code)
            except RuntimeError as err:
                print(f"(baseline failed: {err})")
                return 0
            old_runs = sum(len(s["variants"]) for s in old["submissions"])
            print(
                f"the same class graded in the simulator's process (commit {IN_PROCESS_COMMIT}, {old_runs} runs): "
                f"{old_wall:.1f} s wall, {old_cpu:.1f} s CPU"
            )
            print(
                f"per run: {wall / runs:.3f} s wall now, {old_wall / old_runs:.3f} s then: "
                f"ratio {(wall / runs) / (old_wall / old_runs):.2f}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
