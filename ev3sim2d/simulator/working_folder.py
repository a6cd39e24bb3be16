"""A program's folder as its brick works in it: a copy in the brick's scratch folder.

On an EV3, Brickman starts a program with `brickrun --directory <the program's folder>`: the program
opens its own data files by relative paths, and writes logs and CSV files beside itself.  A brick
works in a copy of what it may read (the program's folder, or only the program's file where that is
all it may read, as a graded file in a class folder), made in its scratch folder: relative paths work
as on the brick, writes land in the copy, and nothing written outlasts the run.

The copy is made by the simulator from files a student controls, so it follows no link (a link to a
lesson's hidden variants is not copied), opens nothing but regular files (no FIFO, no device), and is
bounded: at most MAX_ENTRIES files and folders and MAX_BYTES bytes, MAX_DEPTH folders deep, nearest the
program first, and it stops looking when that is spent (a program run from a folder of thousands of
files costs no more); hidden files and folders (.git, .venv) and __pycache__ are left out, and so is
the temporary folder the scratch folders are made in where it lies inside the program's folder (the
copy would copy itself, and other bricks' scratch folders).  That something did not fit is said in
`note`.
"""

from __future__ import annotations

import os
import stat
from collections import deque
from dataclasses import dataclass
from pathlib import Path

MAX_BYTES = 32 * 2**20
MAX_ENTRIES = 500  # files and folders
MAX_DEPTH = 16
CHUNK = 1 << 20
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
_BINARY = getattr(os, "O_BINARY", 0)


@dataclass
class WorkingFolder:
    """The copy: the folder the brick works in, the program's path in it, and what was left out."""

    folder: Path
    program: Path
    note: str | None = None


def make_working_folder(scratch: Path, readable: list[Path], program: Path) -> WorkingFolder:
    """Copy what the brick may read into scratch; the folder holding (the copy of) the program is its
    working folder.  A readable entry that is the program's file alone gives a folder with that file."""
    budget = _Budget(_identities(scratch, scratch.parent))
    working = None
    for source in readable:
        source = Path(source)
        if source.is_dir() and not source.is_symlink():
            target = _free_name(scratch, source.name or "program")
            target.mkdir()
            _copy_tree(source, target, budget)
            if working is None and _inside(program, source):
                working = WorkingFolder(target, target / program.relative_to(source))
        elif source == program:
            target = _free_name(scratch, program.parent.name or "program")
            target.mkdir()
            _copy_file(source, target / source.name, budget)
            if working is None:
                working = WorkingFolder(target, target / source.name)
    if working is None:  # (the program is not among what it may read: it is copied alone)
        target = _free_name(scratch, "program")
        target.mkdir()
        _copy_file(program, target / program.name, budget)
        working = WorkingFolder(target, target / program.name)
    if not working.program.exists():  # the program itself did not fit: copy it whatever the budget
        working.program.parent.mkdir(parents=True, exist_ok=True)
        _copy_file(program, working.program, _Budget())
    working.note = budget.note()
    return working


class _Budget:
    def __init__(self, never: frozenset = frozenset()) -> None:
        self.files = self.bytes = 0
        self.full = False  # something was left out
        self.never = never  # the folders never copied: (device, inode) of the scratch folder and its own

    def allows(self, size: int) -> bool:
        """Whether a file of this size (a folder: 0) fits; it is counted if so."""
        if self.files + 1 > MAX_ENTRIES or self.bytes + size > MAX_BYTES:
            self.full = True
            return False
        self.files += 1
        self.bytes += size
        return True

    def spent(self) -> bool:
        """Nothing more fits: the copy stops looking (a folder of thousands of files costs no more)."""
        return self.files >= MAX_ENTRIES or self.bytes >= MAX_BYTES

    def note(self) -> str | None:
        if not self.full:
            return None
        return (
            f"its folder holds more than a brick's copy may ({MAX_ENTRIES} files and folders, {MAX_BYTES // 2**20} MB, "
            f"{MAX_DEPTH} folders deep), so the program works in a copy without some of them (the files "
            "nearest the program were copied first); keep a program in a folder of its own"
        )


def _inside(path: Path, folder: Path) -> bool:
    try:
        path.relative_to(folder)
        return True
    except ValueError:
        return False


def _free_name(folder: Path, name: str) -> Path:
    candidate, number = folder / name, 1
    while candidate.exists():
        number += 1
        candidate = folder / f"{name}-{number}"
    return candidate


def _left_out(name: str) -> bool:
    return name.startswith(".") or name == "__pycache__"


def _identities(*folders: Path) -> frozenset:
    """Folders as (device, inode): what names them (a link, a relative path, letter case) does not matter."""
    found = set()
    for folder in folders:
        try:
            info = os.stat(folder)
        except OSError:
            continue
        found.add((info.st_dev, info.st_ino))
    return frozenset(found)


def _copy_tree(source: Path, target: Path, budget: _Budget) -> None:
    """The folder's files and folders, nearest first (breadth first), until the budget is spent."""
    waiting = deque([(source, target, 0)])
    while waiting:
        if budget.spent():
            budget.full = True
            return
        folder, copy, depth = waiting.popleft()
        try:
            entries = sorted(os.scandir(folder), key=lambda e: e.name)
        except OSError:
            continue
        for entry in entries:
            if _left_out(entry.name):
                continue
            if budget.spent():
                budget.full = True
                return
            try:
                if entry.is_dir(follow_symlinks=False):
                    if _identities(Path(entry.path)) & budget.never:
                        continue  # (the temporary folder: its scratch folders are not the program's)
                    if depth + 1 < MAX_DEPTH and budget.allows(0):
                        (copy / entry.name).mkdir()
                        waiting.append((Path(entry.path), copy / entry.name, depth + 1))
                    else:
                        budget.full = True
                elif entry.is_file(follow_symlinks=False):
                    _copy_file(Path(entry.path), copy / entry.name, budget)
            except OSError:
                continue  # (a file that went away, or cannot be read: not copied)


def _copy_file(source: Path, target: Path, budget: _Budget) -> None:
    """A regular file's bytes, read through a descriptor that followed no link; within the budget."""
    fd = os.open(source, os.O_RDONLY | _NOFOLLOW | _NONBLOCK | _BINARY)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode) or not budget.allows(info.st_size):
            return
        with open(target, "xb") as out:
            left = info.st_size
            while left > 0:
                chunk = os.read(fd, min(CHUNK, left))
                if not chunk:
                    break
                out.write(chunk)
                left -= len(chunk)
    finally:
        os.close(fd)
