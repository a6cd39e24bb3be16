"""The source tree of the last commit that ran programs inside the simulator's process, from git:
the benchmarks' baseline, so that each reports the price of the brick process as a ratio."""

from __future__ import annotations

import subprocess
import tarfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IN_PROCESS_COMMIT = "f72c7f3"


def old_code(into: Path) -> Path | None:
    """IN_PROCESS_COMMIT's tree extracted into `into`/code, or None (and why, printed) without the history."""
    archive = into / "code.tar"
    made = subprocess.run(
        ["git", "-C", str(ROOT), "archive", "-o", str(archive), IN_PROCESS_COMMIT],
        capture_output=True,
        text=True,
    )
    if made.returncode != 0:
        print(f"(baseline skipped: git archive {IN_PROCESS_COMMIT} failed: {made.stderr.strip()})")
        return None
    with tarfile.open(archive) as tar:
        tar.extractall(into / "code", filter="data")
    return into / "code"
