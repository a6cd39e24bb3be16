"""A program's folder as its brick works in it: a copy in the brick's scratch folder.

On an EV3, Brickman starts a program with `brickrun --directory <the program's folder>`: the program
opens its own data files by relative paths, and writes logs and CSV files beside itself.  A brick
works in a copy of what it may read (the program's folder, or only the program's file where that is
all it may read, as a graded file in a class folder), made in its scratch folder: relative paths work
as on the brick, and writes land in the copy.  Nothing written outlasts the run, except where the one
who runs a program of their own asks for it (`ev3sim2d run`): then the files the program made at the top
of its folder (a DataLog's CSV, a log) are kept in the program's folder afterwards, as on a brick
(`keep_written`), never over a file there (a name taken gets a number: log.csv, log-2.csv, since a
run's virtual clock gives a DataLog the same name each run), never through a link, at most KEEP_FILES
of KEEP_BYTES each.

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
from dataclasses import dataclass, field
from pathlib import Path

MAX_BYTES = 32 * 2**20
MAX_ENTRIES = 500  # files and folders
MAX_DEPTH = 16
KEEP_FILES = 20  # files a program made that a run keeps, at most ...
KEEP_BYTES = 16 * 2**20  # ... of this size each
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
    origin: Path | None = None  # the folder `folder` is a copy of (None: the program was copied alone)
    copied: dict = field(default_factory=dict)  # name -> (size, mtime) at the top of `folder` once made


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
                working = WorkingFolder(target, target / program.relative_to(source), origin=source)
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
    working.copied = _top_files(working.folder)
    return working


def _top_files(folder: Path) -> dict:
    """name -> (size, modification time) of the entries at the top of a folder (links not followed)."""
    found = {}
    for entry in os.scandir(folder):
        info = entry.stat(follow_symlinks=False)
        found[entry.name] = (info.st_size, info.st_mtime_ns)
    return found


def keep_written(working: WorkingFolder) -> tuple[list[str], list[str]]:
    """Copy the regular files the program made or changed at the top of its working folder into the
    folder it is a copy of: (names kept, why others were not).  A name taken there is left alone, and the target is
    opened so that it follows no link (O_EXCL, O_NOFOLLOW): whatever the folder holds, nothing is written
    but a new file.  Called once the brick has ended."""
    if working.origin is None:
        return [], []
    kept, not_kept = [], []
    try:
        now = _top_files(working.folder)
    except OSError:
        return [], []
    names = sorted(name for name, seen in now.items() if working.copied.get(name) != seen)
    for name in names:
        if _left_out(name) or name.endswith((".pyc", ".part")):
            continue
        if len(kept) >= KEEP_FILES:
            not_kept.append(f"{name} (only the first {KEEP_FILES} files a program makes are kept)")
            continue
        try:
            why = _keep_file(working.folder / name, working.origin, name)
        except OSError as err:
            why = f"{err.strerror or err}"
        if why is None or why.startswith("as "):
            kept.append(name if why is None else f"{name} {why}")
        elif why:
            not_kept.append(f"{name} ({why})")
    return kept, not_kept


def _keep_file(source: Path, folder: Path, name: str) -> str | None:
    """None once copied as `name`, "as NAME" once copied under a free name; why not otherwise ("" for
    what is not a file: not worth a word)."""
    fd = os.open(source, os.O_RDONLY | _NOFOLLOW | _NONBLOCK | _BINARY)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            return ""
        if info.st_size > KEEP_BYTES:
            return f"larger than {KEEP_BYTES // 2**20} MB"
        stem, dot, extension = name.rpartition(".") if "." in name.lstrip(".") else (name, "", "")
        for number in range(1, 100):
            chosen = name if number == 1 else f"{stem}-{number}{dot}{extension}"
            try:
                out = os.open(
                    folder / chosen, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW | _BINARY, 0o644
                )
                break
            except FileExistsError:
                continue
        else:
            return "its name and 98 numbered ones are taken there"
        try:
            left = info.st_size
            while left > 0:
                chunk = os.read(fd, min(CHUNK, left))
                if not chunk:
                    break
                os.write(out, chunk)
                left -= len(chunk)
        finally:
            os.close(out)
    finally:
        os.close(fd)
    return None if chosen == name else f"as {chosen}"


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
