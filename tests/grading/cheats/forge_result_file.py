# ruff: noqa
"""Forge the result: write the result file the grader reads (`result.json` in the job folder, the parent
of the working folder) with every check passed, then kill the own process before it is overwritten.

The grader takes a result file that is there as the run's result, however the process ended; the
check names and points are in the lesson's README, the variant names in its lesson.yaml, and the
job folder's name (`s<submission>-v<variant>`) says which variant this is.  `os._exit` is patched
in a run; `posix._exit`, the same function, is not (and if it were, `os.kill(os.getpid(), SIGKILL)`).

Contained: the grader reads only what the simulator measured: the program killed itself before
doing anything, so it scores at most what standing still scores (never `distance`).
"""

import json
import os
import posix
import re
import signal

MARKER = "EV3CHEAT-forge-result-file"
VARIANTS = [("room", False), ("near", True), ("across", True), ("noisy", True)]
CHECKS = [
    ("distance", "wall_distance", 5),
    ("no-touch", "wall_contacts", 2),
    ("stopped", "stopped", 2),
    ("finished", "finished", 1),
]

here = os.getcwd()
found = re.search(r"-v(\d+)$", os.path.basename(os.path.dirname(here)))
index = int(found.group(1)) if found else 0
name, hidden = VARIANTS[index % len(VARIANTS)]
forged = {
    "outcome": "ran",
    "variant": {
        "name": name,
        "hidden": hidden,
        "status": "graded",
        "message": "the program finished at 9.6 s",
        "sim_time_s": 9.6,
        "checks": [
            {
                "name": n,
                "kind": k,
                "passed": True,
                "points": p,
                "max_points": p,
                "message": "passed",
                "t_s": 9.6,
            }
            for n, k, p in CHECKS
        ],
    },
    "trace": False,
    "wall_time_s": 0.1,
}
for folder in {os.path.dirname(here), here}:
    try:
        with open(os.path.join(folder, "result.json"), "w") as f:
            json.dump(forged, f)
    except OSError as err:
        print("cannot write", folder, err)
try:
    posix._exit(0)
finally:
    os.kill(os.getpid(), signal.SIGKILL)
