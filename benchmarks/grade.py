#!/usr/bin/env python3
"""How long grading a class takes: thirty submissions of `line-follow`, two at a time.

The class is made up: thirty line followers as students write them, each with its own speed
and steering (most follow the line; some are too fast or too slow, one never starts), each in a
student's folder or as a single file.  They are graded with the command a teacher types:

    ev3sim2d grade line-follow CLASS --jobs 2 --json results.json

Target: under 30 s of wall time on a 2-core machine.
Run:  python benchmarks/grade.py [--jobs 2] [--students 30] [--keep DIR]
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

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


def main() -> int:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--students", type=int, default=30)
    parser.add_argument("--keep", metavar="DIR", help="make the class in DIR and keep it (and results.json)")
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        root = Path(args.keep or scratch)
        folder = root / "class"
        folder.mkdir(parents=True, exist_ok=True)
        make_class(folder, args.students)
        results = root / "results.json"
        results.unlink(missing_ok=True)
        command = [
            sys.executable,
            "-m",
            "ev3sim2d",
            "grade",
            "line-follow",
            str(folder),
            "--jobs",
            str(args.jobs),
        ]
        command += ["--json", str(results), "--quiet"]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run(command, capture_output=True, text=True)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        if done.returncode != 0 or not results.is_file():
            print(done.stdout, done.stderr, file=sys.stderr)
            return 1
        data = json.loads(results.read_text())
        submissions = data["submissions"]
        runs = sum(len(s["variants"]) for s in submissions)
        full = sum(1 for s in submissions if s["score"] == s["max_score"])
        statuses = sorted({s["status"] for s in submissions})
    print(
        f"graded {len(submissions)} submissions of line-follow ({runs} runs, {len(data['variants'])} variants each) "
        f"with --jobs {args.jobs} in {wall:.1f} s wall ({full} with full marks; statuses: {', '.join(statuses)})"
    )
    print(
        f"CPU time of the grader and its workers: {cpu:.1f} s ({cpu / args.jobs:.1f} s per job slot: "
        "the wall time on an otherwise idle machine)"
    )
    print(f"target: under 30 s -> {'met' if wall < 30 else 'NOT met'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
