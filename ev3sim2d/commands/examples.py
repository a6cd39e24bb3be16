"""`ev3sim2d examples [DIR]`: copy the example programs that ship with ev3sim2d into a folder (./examples).

They ship inside the package (a wheel holds them as `ev3sim2d/_examples/`, setup.py), so the README's
commands (`ev3sim2d run examples/line_follower.py --maze line`) work after `pip install ev3sim2d`, in
any folder, once this has copied them there. A file that is already there and differs is left alone
unless `--force`: the programs are meant to be edited.
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from .exit_codes import EXIT_OK, fail

NAME = "examples"
HELP = "copy the example programs (and their robot files) into a folder, ./examples by default"


def shipped_examples_dir() -> Path:
    """The example programs that come with ev3sim2d (an installed copy first, else the repository's)."""
    package = Path(__file__).resolve().parents[1]
    installed = package / "_examples"
    return installed if installed.is_dir() else package.parent / "examples"


def example_files() -> list[Path]:
    """Every shipped example file (programs and robot files), relative to the examples folder, sorted."""
    root = shipped_examples_dir()
    return sorted(
        path.relative_to(root)
        for path in root.rglob("*")
        if path.is_file() and "__pycache__" not in path.parts and path.suffix in (".py", ".yaml")
    )


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("dir", nargs="?", default="examples", help="where to copy them (default: ./examples)")
    parser.add_argument("--force", action="store_true", help="overwrite files there that differ")


def main(args) -> int:
    source, target = shipped_examples_dir(), Path(args.dir)
    files = example_files()
    if not files:
        return fail(f"no example programs found in {source} (a broken install?)", 1)
    if target.exists() and not target.is_dir():
        return fail(f"{target} is a file; give a folder to copy the examples into")
    changed = [
        name
        for name in files
        if (target / name).exists() and (target / name).read_bytes() != (source / name).read_bytes()
    ]
    if changed and not args.force:
        names = ", ".join(str(target / name) for name in changed)
        return fail(f"{names} already there and different; add --force to overwrite, or give another folder")
    for name in files:
        (target / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(source / name, target / name)
    programs = [name for name in files if name.suffix == ".py"]
    print(
        f"copied {len(programs)} example programs to {target}/ (and {len(files) - len(programs)} robot files)"
    )
    first = target / "line_follower.py"
    print(f"try: ev3sim2d run {first.as_posix()} --maze line --time 30 --png end.png")
    return EXIT_OK
