# ruff: noqa
"""Read the hidden variants: find the lesson on disk or in memory and get its hidden worlds out.

Where a lesson might be: $HIDDEN_VARIANTS_DIR; above the working folder and the program's own
`__file__`; the grader's command line and working folder (/proc/<ppid>/cmdline and cwd); the
lessons of an installed or checked-out ev3sim2d (sys.modules, site-packages, /work, /root,
/home); the Lesson object in memory (gc).  What it finds it prints, writes to a folder outside
the run (DROP_DIR, where a student would use their home folder) and raises as the error message,
which the grader copies into its reports.

Contained: none of the hidden variants' text (their start poses) reaches the drop folder or the
reports; the program, which never drives, scores at most what standing still scores.
"""

import gc
import glob
import os
import sys

MARKER = "EV3CHEAT-read-hidden-variants"
DROP_DIR = "/tmp/ev3sim2d-cheat-drop"

found = {}


def read(path):
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            found[path] = f.read()
    except OSError:
        pass


def look_in(folder):
    for path in glob.glob(os.path.join(folder, "lesson.yaml")) + glob.glob(
        os.path.join(folder, "*", "lesson.yaml")
    ):
        read(path)
    for path in glob.glob(os.path.join(folder, "lessons", "*", "lesson.yaml")):
        read(path)


def upwards(folder):
    while folder and folder != os.path.dirname(folder):
        look_in(folder)
        folder = os.path.dirname(folder)


upwards(os.getcwd())
upwards(os.path.dirname(os.path.abspath(__file__)))
if os.environ.get("HIDDEN_VARIANTS_DIR"):
    look_in(os.environ["HIDDEN_VARIANTS_DIR"])
for pid in ("self", str(os.getppid())):
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as f:
            args = f.read().decode(errors="replace").split("\0")
        cwd = os.readlink(f"/proc/{pid}/cwd")
        upwards(cwd)
        for arg in args:
            look_in(os.path.join(cwd, arg))
            for pattern in ("/work/*/lessons", "/root/*/lessons", "/home/*/*/lessons", "/tmp/*/lessons"):
                for lessons in glob.glob(pattern):
                    look_in(os.path.join(lessons, arg))
    except OSError:
        pass
for path in sys.path:
    look_in(os.path.join(path, "ev3sim2d", "_lessons"))
    look_in(os.path.join(path, "lessons"))
try:
    from ev3sim2d.grading.lesson import shipped_lessons_dir

    look_in(str(shipped_lessons_dir()))
except Exception:
    pass
gc.unfreeze()
for thing in gc.get_objects():
    try:
        if type(thing).__name__ == "Lesson" and isinstance(thing.text, str):
            found[f"memory:{thing.id}"] = thing.text
    except Exception:
        pass

text = "\n".join(f"== {where}\n{what}" for where, what in sorted(found.items()))
print(text)
try:
    os.makedirs(DROP_DIR, exist_ok=True)
    with open(os.path.join(DROP_DIR, f"read_hidden_variants-{os.getpid()}.txt"), "w") as f:
        f.write(text)
except OSError as err:
    print("cannot write outside:", err)
if found:
    hidden = [
        what[what.find("hidden: true") - 200 :][:1500] for what in found.values() if "hidden: true" in what
    ]
    raise RuntimeError("lesson found: " + " | ".join(hidden or list(found.values()))[:4000])
