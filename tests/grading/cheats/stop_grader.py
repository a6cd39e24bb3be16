# ruff: noqa
"""Freeze the grader: SIGSTOP to the parent and every ancestor, so that the class run never finishes
(and the CI job hangs until its own timeout).  What it did it notes in DROP_DIR.

Contained: the program cannot signal the grader (it is not its parent, nor visible): the class run
ends in its usual time with exit status 0; this program stands still and scores what standing still scores.
"""

import os
import signal

MARKER = "EV3CHEAT-stop-grader"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"


def parent_of(pid):
    with open(f"/proc/{pid}/stat") as f:
        return int(f.read().rsplit(")", 1)[1].split()[1])


done = [f"pid {os.getpid()} ppid {os.getppid()}"]
pid = os.getppid()
while pid > 1:
    try:
        os.kill(pid, signal.SIGSTOP)
        done.append(f"stopped {pid}")
        pid = parent_of(pid)
    except OSError as err:
        done.append(f"cannot stop {pid}: {err}")
        break
try:
    with open(os.path.join(DROP_DIR, f"stop_grader-{os.getpid()}.txt"), "w") as f:
        f.write("\n".join(done) + "\n")
except OSError:
    pass
