# ruff: noqa
"""Lower the bar: walk gc.get_objects() to the lesson's checks and widen the `distance` check to anything.

The lesson was loaded by the grader before it forked this run, and frozen out of gc's sight
(gc.freeze); gc.unfreeze() brings it back.  Every object with `min_cm` and `max_cm` (the
wall_distance check) then gets 0 and 10 metres, and a robot that stands still passes it.

Contained: no check of the lesson lives in the program's process: standing still scores what
standing still scores (never `distance`).
"""

import gc

MARKER = "EV3CHEAT-lower-threshold"

gc.unfreeze()
changed = 0
for thing in gc.get_objects():
    try:
        if hasattr(thing, "min_cm") and hasattr(thing, "max_cm") and hasattr(thing, "evaluate"):
            thing.min_cm, thing.max_cm = 0.0, 1000.0
            changed += 1
    except Exception:
        pass
print("checks changed:", changed)
