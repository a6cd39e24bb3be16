"""Packaging: setup.cfg says it all, except that a wheel carries the shipped worlds, lessons and the shim.

The repository keeps `mazes/` and the `ev3dev2/` shim at its top level (for people to find and
edit). Installing them as top-level packages would shadow a real python-ev3dev2, so a wheel gets
them inside ev3sim2d instead, as `ev3sim2d/_mazes/`, `_lessons/` and `_shim/ev3dev2/`, where only a
simulated run looks. An editable install reads them from the repository directly.
"""

import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

ROOT = Path(__file__).resolve().parent


class BuildWithWorldsAndShim(build_py):
    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        target = Path(self.build_lib) / "ev3sim2d"
        shutil.copytree(ROOT / "mazes", target / "_mazes", dirs_exist_ok=True)
        shutil.copytree(
            ROOT / "lessons",
            target / "_lessons",
            dirs_exist_ok=True,
            ignore=shutil.ignore_patterns("__pycache__", "*.pyc"),
        )
        shutil.copytree(
            ROOT / "ev3dev2",
            target / "_shim" / "ev3dev2",
            dirs_exist_ok=True,
            ignore=shutil.ignore_patterns("__pycache__", "*.pyc"),
        )


setup(cmdclass={"build_py": BuildWithWorldsAndShim})
