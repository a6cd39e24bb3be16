"""`ev3sim2d lessons [--dir DIR]`: the lessons there are, one line each: the name to grade with, the
title and the first sentence of the goal.

The lessons listed are the shipped ones (as a student's install has them: no hidden variants, no
solutions) and, with `--dir`, a teacher's own: DIR may be a lesson folder or a folder of them (for
example a teacher's copy of the repository's `lessons/`). A teacher's lesson is named by its path,
which is what `ev3sim2d grade` takes.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from ..grading.lesson import LESSON_FILE, list_shipped_lessons, load_lesson
from ..world.source_error import WorldFileError
from .exit_codes import EXIT_OK, EXIT_USAGE

NAME = "lessons"
HELP = "list the lessons (shipped, and a teacher's with --dir): name, title and goal"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument(
        "--dir",
        action="append",
        default=[],
        metavar="DIR",
        help="also list the lessons in DIR: a lesson folder or a folder of lesson folders (repeatable)",
    )


def first_sentence(text: str) -> str:
    """The goal's first sentence, on one line."""
    flat = " ".join(text.split())
    return re.split(r"(?<=[.!?])\s", flat, maxsplit=1)[0]


def lesson_folders(folder: Path) -> list[Path]:
    """A lesson folder itself, or the lesson folders inside it, sorted."""
    if (folder / LESSON_FILE).is_file():
        return [folder]
    return sorted(path.parent for path in folder.glob(f"*/{LESSON_FILE}"))


def main(args) -> int:
    entries: list[str | Path] = list(list_shipped_lessons())
    for name in args.dir:
        folder = Path(name)
        found = lesson_folders(folder) if folder.is_dir() else []
        if not found:
            print(
                f"ev3sim2d: error: {folder}: no lesson folder (with a {LESSON_FILE}) there", file=sys.stderr
            )
            return EXIT_USAGE
        entries += found
    status = EXIT_OK
    rows = []
    for entry in entries:
        try:
            lesson = load_lesson(entry)
        except (WorldFileError, OSError) as error:
            print(f"ev3sim2d: error: lesson {entry}: {error}", file=sys.stderr)
            status = EXIT_USAGE
            continue
        rows.append((str(entry), lesson.title, first_sentence(lesson.goal)))
    width = max((len(name) for name, _, _ in rows), default=0)
    for name, title, goal in rows:
        print(f"{name:{width}}  {title}: {goal}")
    return status
