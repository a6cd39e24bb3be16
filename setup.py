"""Packaging: setup.cfg says it all, except that a wheel carries the shipped worlds, lessons and the shim.

The repository keeps `mazes/` and the `ev3dev2/` and `pybricks/` shims at its top level (for people
to find and edit). Installing them as top-level packages would shadow a real python-ev3dev2, or the
`pybricks` stubs editors complete from, so a wheel gets them inside ev3sim2d instead, as
`ev3sim2d/_mazes/`, `_lessons/`, `_shim/ev3dev2/` and `_shim/pybricks/`, where only a simulated run looks; the example programs go in as `ev3sim2d/_examples/`, for `ev3sim2d examples` to
copy out. An editable install reads them from the repository directly.

A wheel is what students install, so its lessons are what students may read: each lesson's `hidden/`
folder (the hidden variants and their worlds), its reference `solution.py` (and `solution_pybricks.py`, the
same in Pybricks) and its deliberately wrong programs (`wrong/`) stay in the repository, for teachers
and the tests (tests/lessons/test_wheel.py).
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent
NOT_SHIPPED_FROM_LESSONS = ("hidden", "solution.py", "solution_pybricks.py", "wrong", "__pycache__", "*.pyc")


class BuildWithWorldsAndShim(build_py):
    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        target = Path(self.build_lib) / "ev3sim2d"
        # an earlier build's copy may hold files that are no longer shipped (a hidden world): start afresh
        shutil.rmtree(target / "_lessons", ignore_errors=True)
        shutil.copytree(ROOT / "mazes", target / "_mazes", dirs_exist_ok=True)
        shutil.copytree(
            ROOT / "lessons",
            target / "_lessons",
            dirs_exist_ok=True,
            ignore=shutil.ignore_patterns(*NOT_SHIPPED_FROM_LESSONS),
        )
        shutil.rmtree(target / "_examples", ignore_errors=True)
        shutil.copytree(
            ROOT / "examples", target / "_examples", ignore=shutil.ignore_patterns("__pycache__", "*.pyc")
        )
        for shim in ("ev3dev2", "pybricks"):
            shutil.copytree(
                ROOT / shim,
                target / "_shim" / shim,
                dirs_exist_ok=True,
                ignore=shutil.ignore_patterns("__pycache__", "*.pyc"),
            )


setup(cmdclass={"build_py": BuildWithWorldsAndShim})
