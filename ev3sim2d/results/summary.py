"""The JSON summary of a run (`--summary`): how it ended and where each robot went, read from the trace."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .output_files import write_file
from .trace import POSE_COLUMNS, Trace


def robot_summary(trace: Trace, index: int) -> dict:
    """Start and end pose, path length and wall contacts of one robot."""
    poses = trace.poses(index)
    steps = np.diff(poses[:, :2], axis=0)
    path = float(np.hypot(steps[:, 0], steps[:, 1]).sum()) if len(steps) else 0.0
    motion = trace.motion()
    touching = motion[:, trace.robot_columns(index)][:, POSE_COLUMNS.index("touching")] if len(motion) else []
    contacts = int(np.count_nonzero(np.diff(np.concatenate([[0.0], touching])) > 0)) if len(touching) else 0
    x, y, heading = poses[-1]
    return {
        "name": trace.robots[index]["name"],
        "start": trace.robots[index]["start"],
        "end": {
            "x_cm": round(float(x), 3),
            "y_cm": round(float(y), 3),
            "heading_deg": round(float(heading), 3),
        },
        "path_cm": round(path, 3),
        "wall_contacts": contacts,
    }


def run_summary(result, programs: list[str], maze: str, seed: int, time_limit_s: float | None) -> dict:
    trace = result.trace
    return {
        "status": result.status,
        "reason": result.reason,
        "sim_time_s": round(result.sim_time_s, 6),
        "wall_time_s": round(result.wall_time_s, 4),
        "fingerprint": trace.fingerprint(),
        "programs": [str(p) for p in programs],
        "maze": str(maze),
        "seed": seed,
        "time_limit_s": time_limit_s,
        "output": [line.text for line in trace.output],
        "error": result.error,
        "notes": list(getattr(result, "notes", [])),  # what the user should know that is not an error
        "robots": [robot_summary(trace, i) for i in range(len(trace.robots))],
    }


def write_summary(summary: dict, path: str | Path) -> None:
    write_file(path, json.dumps(summary, indent=2) + "\n")
