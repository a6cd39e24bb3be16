#!/usr/bin/env python3
"""What a served world costs: 4 robots via `ev3sim2d serve` + 4 `ev3sim2d join`s on loopback, against the
same run in one `ev3sim2d run` command, measured in one run on this machine.

The programs are four sumo fighters in mazes/sumo-4.yaml (examples/sumo.py, each with its own turn,
charge and range, as four students would write them).  Both ways must give the same fingerprint (it
is checked); the network may change only the wall time.  Each pair runs `run` and `serve` one after
the other, and the ratio is taken per pair: the machine is shared, so compare ratios, not seconds.

Two wall times per way: `session` is the simulation alone (from the summary's wall_time_s: the world
and its bricks in lockstep, from the first tick to the last), `command` is from the command's start to
the end of the last process (interpreters, bricks, joining, writing the summary).

Run:  python benchmarks/serve_join.py [--seconds 30] [--pairs 3]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SUMO = ROOT / "examples" / "sumo.py"
STUDENTS = {  # what each student changed in examples/sumo.py
    "s1.py": [],
    "s2.py": [("tank.on(25, -25)", "tank.on(-25, 25)"), ("SEES_CM = 70", "SEES_CM = 40")],
    "s3.py": [("tank.on(100, 100)", "tank.on(70, 70)"), ("SEES_CM = 70", "SEES_CM = 50")],
    "s4.py": [
        ("tank.on(25, -25)", "tank.on(-40, 40)"),
        ("tank.on(100, 100)", "tank.on(90, 90)"),
        ("SEES_CM = 70", "SEES_CM = 30"),
    ],
}


def write_programs(folder: Path) -> list[Path]:
    paths = []
    for name, changes in STUDENTS.items():
        text = SUMO.read_text()
        for old, new in changes:
            assert old in text, old
            text = text.replace(old, new)
        (folder / name).write_text(text)
        paths.append(folder / name)
    return paths


def _env() -> dict:
    return {**os.environ, "PYTHONHASHSEED": "0"}


def _command(*args: str) -> list[str]:
    return [sys.executable, "-m", "ev3sim2d", *args]


def one_command(folder: Path, programs: list[Path], seconds: float) -> tuple[float, dict]:
    summary = folder / "run.json"
    start = time.perf_counter()
    subprocess.run(
        _command("run", *map(str, programs), "--maze", "sumo-4", "--time", str(seconds), "--quiet",
                 "--summary", str(summary)),
        cwd=folder, env=_env(), check=True, capture_output=True,
    )  # fmt: skip
    return time.perf_counter() - start, json.loads(summary.read_text())


def served(folder: Path, programs: list[Path], seconds: float) -> tuple[float, dict]:
    summary = folder / "served.json"
    log = folder / "serve.err"
    start = time.perf_counter()
    with open(log, "w") as err:
        server = subprocess.Popen(
            _command("serve", "--maze", "sumo-4", "--robots", "4", "--port", "0", "--time", str(seconds),
                     "--quiet", "--summary", str(summary)),
            cwd=folder, env=_env(), stdout=subprocess.DEVNULL, stderr=err,
        )  # fmt: skip
        port = None
        while port is None:
            found = re.search(r"serving .* on 127\.0\.0\.1:(\d+)", log.read_text())
            if found:
                port = found.group(1)
            elif server.poll() is not None:
                raise SystemExit(f"serve ended:\n{log.read_text()}")
            else:
                time.sleep(0.005)
        joins = [
            subprocess.Popen(
                _command("join", f"127.0.0.1:{port}", str(p), "--robot", str(i + 1), "--quiet"),
                cwd=folder,
                env=_env(),
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )  # fmt: skip
            for i, p in enumerate(programs)
        ]
        if server.wait(timeout=600) != 0:
            raise SystemExit(f"serve failed:\n{log.read_text()}")
        for join in joins:
            join.wait(timeout=60)
    return time.perf_counter() - start, json.loads(summary.read_text())


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--seconds", type=float, default=30.0, help="simulated seconds per run (default 30)")
    parser.add_argument("--pairs", type=int, default=3, help="pairs of runs (default 3)")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="ev3sim2d-serve-bench-") as tmp:
        folder = Path(tmp)
        programs = write_programs(folder)
        for pair in range(args.pairs):
            run_wall, ran = one_command(folder, programs, args.seconds)
            serve_wall, joined = served(folder, programs, args.seconds)
            if joined["fingerprint"] != ran["fingerprint"]:
                raise SystemExit(f"different runs: {joined['fingerprint']} != {ran['fingerprint']}")
            rows.append((ran["wall_time_s"], joined["wall_time_s"], run_wall, serve_wall))
            print(
                f"pair {pair + 1}: session {ran['wall_time_s']:.2f} s (run) vs {joined['wall_time_s']:.2f} s "
                f"(serve + 4 joins), ratio {joined['wall_time_s'] / ran['wall_time_s']:.2f}; command "
                f"{run_wall:.2f} s vs {serve_wall:.2f} s, ratio {serve_wall / run_wall:.2f}; "
                f"fingerprint {ran['fingerprint']} both",
                flush=True,
            )
    session_ratio = statistics.median(r[1] / r[0] for r in rows)
    command_ratio = statistics.median(r[3] / r[2] for r in rows)
    speed_run = statistics.median(args.seconds / r[0] for r in rows)
    speed_served = statistics.median(args.seconds / r[1] for r in rows)
    print(
        f"\n4 robots, {args.seconds:g} s simulated, {args.pairs} pairs (medians):\n"
        f"  one `run` command:        {speed_run:6.1f}x real time\n"
        f"  `serve` + 4 `join`s:      {speed_served:6.1f}x real time\n"
        f"  served / one command:     session {session_ratio:.2f}, whole command {command_ratio:.2f} (wall time)"
    )


if __name__ == "__main__":
    main()
