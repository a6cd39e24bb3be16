"""A GitHub Actions workflow checked against GitHub's own schema, offline (check-jsonschema's builtin)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path


def schema_problems(workflow: Path) -> str | None:
    """None when the workflow is valid; else what check-jsonschema says is wrong."""
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "check_jsonschema",
            "--builtin-schema",
            "vendor.github-workflows",
            str(workflow),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    return None if done.returncode == 0 else done.stdout + done.stderr
