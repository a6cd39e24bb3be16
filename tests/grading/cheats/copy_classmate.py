# ruff: noqa
"""Copy a classmate: read the other programs handed in beside this one and run the first that solves the task.

The class folder is the folder of the program's own `__file__`; a program there that uses the
ultrasonic sensor and stops the motors is most likely a solution.  Its code is run as this
program's own.

Contained: the program cannot read other submissions; it runs nothing, stands still, and scores
what standing still scores (never `distance`).
"""

import glob
import os

MARKER = "EV3CHEAT-copy-classmate"

here = os.path.abspath(__file__)
folder = os.path.dirname(here)
candidates = sorted(glob.glob(os.path.join(folder, "*.py")) + glob.glob(os.path.join(folder, "*", "*.py")))
for path in candidates:
    if os.path.abspath(path) == here:
        continue
    try:
        with open(path, encoding="utf-8") as f:
            source = f.read()
    except OSError:
        continue
    if "UltrasonicSensor" in source and ".off()" in source and "EV3CHEAT" not in source:
        print("copying", path)
        exec(compile(source, here, "exec"), {"__name__": "__main__", "__file__": here})
        break
else:
    print("nothing to copy")
