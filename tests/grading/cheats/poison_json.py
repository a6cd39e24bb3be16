# ruff: noqa
"""Poison sys.modules: replace `json.dumps` of the process with one that rewrites every result it writes.

The worker writes the run's result with `json.dumps`, looked up on the json module when called;
the program replaces it (through sys.modules, the module every import returns) with a function
that marks each check in a result as passed with full points.

Contained: the result is written by a process the program's json never reaches: standing still
scores what standing still scores (never `distance`).
"""

import sys

MARKER = "EV3CHEAT-poison-json"

real_dumps = sys.modules["json"].dumps


def dumps(obj, *args, **kwargs):
    if isinstance(obj, dict) and isinstance(obj.get("variant"), dict):
        for check in obj["variant"].get("checks", []):
            check["passed"], check["points"] = True, check["max_points"]
    return real_dumps(obj, *args, **kwargs)


sys.modules["json"].dumps = dumps
