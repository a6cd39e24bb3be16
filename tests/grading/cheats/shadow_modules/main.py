# ruff: noqa
"""Shadow modules: a student's folder that holds modules named like ones the simulator or the brick's own
code may import after the student's folder is put first on sys.path (json, socket, selectors, struct,
zlib, base64, queue, and a package `ev3sim2d`).  Each, when imported, gives every check full marks if a
scorer is within reach (see `_payload.py`), notes in DROP_DIR which process imported it, then stands
in for the real module so that nothing breaks.  main.py itself does nothing.

Contained: whatever imports these modules can reach no scorer: the program scores what standing
still scores.
"""

MARKER = "EV3CHEAT-shadow-modules"
print("main does nothing")
