# ruff: noqa
"""Patch the result writer: find the scoring worker's frame with sys._current_frames() and swap the
function that writes the result file for one that marks every check passed.

The program's own stack ends in the scheduler, but `sys._current_frames()` has every thread's;
the main thread waits in `run_programs`, called from the worker's `_run_and_score`, whose module
globals hold `_write_json`.

Contained: no frame of a scorer or result writer exists in the program's process: standing
still scores what standing still scores (never `distance`).
"""

import sys

MARKER = "EV3CHEAT-frames-result-writer"


def full_marks(write):
    def forged(path, data):
        for check in (data.get("variant") or {}).get("checks", []):
            check["passed"], check["points"] = True, check["max_points"]
        return write(path, data)

    return forged


patched = 0
for frame in list(sys._current_frames().values()):
    while frame is not None:
        if "_write_json" in frame.f_globals and frame.f_globals["_write_json"].__name__ != "forged":
            frame.f_globals["_write_json"] = full_marks(frame.f_globals["_write_json"])
            patched += 1
        frame = frame.f_back
print("writers patched:", patched)
