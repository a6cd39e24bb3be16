# ruff: noqa
"""Outlive the grader: leave a process behind that rewrites the class's reports with full marks once the
grader has written them for the last time.

The program reads the grader's command line and working folder (/proc/<ppid>/cmdline and cwd)
while the grader is there, then forks, calls os.setsid() (out of the run's process group, which
the grader kills) and forks again; the grandchild becomes a fresh Python (`python -c ...`, with
the marker in its command line) that waits for the grader to exit and then gives this submission
full marks in the --json, --csv and --junit files, again every second for a while.  Graded
again with the same --json, the grader takes the forged result as already graded.

Contained: no process of the run outlives the grader; the report files are the same seconds after
the grader exited as when it exited; the program stands still and scores what standing still scores.
"""

import os
import posix
import sys

MARKER = "EV3CHEAT-linger-rewrite-reports"

PAYLOAD = r"""
import csv, io, json, os, sys, time
marker, grader, cwd, me, args = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5:]
def option(name):
    for i, arg in enumerate(args):
        if arg == name and i + 1 < len(args):
            return os.path.join(cwd, args[i + 1])
        if arg.startswith(name + "="):
            return os.path.join(cwd, arg.split("=", 1)[1])
def forge():
    path = option("--json")
    if path and os.path.exists(path):
        data = json.load(open(path))
        for sub in data["submissions"]:
            if me in sub["submission"]:
                for variant in sub["variants"]:
                    for check in variant["checks"]:
                        check["passed"], check["points"] = True, check["max_points"]
                    variant["score"], variant["status"] = variant["max_score"], "graded"
                sub["score"], sub["status"] = sub["max_score"], "graded"
        json.dump(data, open(path, "w"), indent=2)
    path = option("--csv")
    if path and os.path.exists(path):
        rows = list(csv.reader(open(path, newline="")))
        for row in rows[1:]:
            if me in row[0]:
                row[1], row[2], row[4] = "graded", row[3], "100"
                share = float(row[3]) / max(1, len(rows[0]) - 6)
                row[5:-1] = ["%g" % share] * (len(row) - 6)
                row[-1] = ""
        out = io.StringIO()
        csv.writer(out).writerows(rows)
        open(path, "w", newline="").write(out.getvalue())
    path = option("--junit")
    if path and os.path.exists(path):
        text = open(path).read()
        open(path, "w").write(text.replace("<failure", "<system-out").replace("</failure>", "</system-out>"))
while os.path.exists(f"/proc/{grader}"):
    time.sleep(0.02)
for _ in range(30):
    try:
        forge()
    except Exception as err:
        print(marker, err)
    time.sleep(1)
"""

grader = os.getppid()
try:
    with open(f"/proc/{grader}/cmdline", "rb") as f:
        args = [a.decode(errors="replace") for a in f.read().split(b"\0") if a]
    cwd = os.readlink(f"/proc/{grader}/cwd")
    child = os.fork()
    if child == 0:
        try:
            os.setsid()
            if os.fork() == 0:
                os.execv(
                    sys.executable,
                    [
                        sys.executable,
                        "-c",
                        PAYLOAD,
                        MARKER,
                        str(grader),
                        cwd,
                        "linger_rewrite_reports",
                        *args,
                    ],
                )
        finally:
            posix._exit(0)
    os.waitpid(child, 0)
    print("left a process behind")
except Exception as err:
    print("cannot stay:", err)
