"""What is handed in: one student's program (a file, or a folder of modules) and the file to run.

`ev3sim2d grade LESSON PROG...` takes files and folders:
- a `.py` file is one submission;
- a folder holding the entry file (`main.py` unless `--entry` names another) is
  one student's submission, with all its modules;
- any other folder is a class: each `.py` file in it, and each sub-folder, is
  one student's submission; in a sub-folder the entry file, else its only
  `.py` file, is the program to run.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from pathlib import Path

DEFAULT_ENTRY = "main.py"
SKIPPED = ("__pycache__",)


@dataclass(frozen=True)
class Submission:
    """A student's program: `name` as reports show it, the `entry` to run, and the files whose content counts."""

    name: str
    path: Path
    entry: Path | None
    files: tuple[Path, ...]
    problem: str | None = None  # why it cannot be run (no program found), shown as the result

    def key(self, lesson_digest: str) -> str:
        """Same lesson and same files give the same key (to reuse a result when grading resumes)."""
        h = hashlib.sha256(lesson_digest.encode())
        h.update(str(self.entry.name if self.entry else "").encode())
        for path in self.files:
            h.update(str(path.relative_to(self.path) if self.path.is_dir() else path.name).encode())
            try:
                h.update(path.read_bytes())
            except OSError:
                h.update(b"<unreadable>")
        if self.problem:
            h.update(self.problem.encode())
        return h.hexdigest()[:20]


def _python_files(folder: Path) -> list[Path]:
    return sorted(
        p
        for p in folder.rglob("*.py")
        if not any(part in SKIPPED or part.startswith(".") for part in p.relative_to(folder).parts)
    )


def _links(path: Path) -> list[Path]:
    """Symbolic links in a submission: the grader reads the files as the teacher, so a link could show
    a student any file the teacher may read (in a syntax error's message, say).  None are taken."""
    if path.is_symlink():
        return [path]
    if not path.is_dir():
        return []
    found = []
    for folder, dirs, files in os.walk(path):
        found += [Path(folder) / n for n in dirs + files if os.path.islink(os.path.join(folder, n))]
    return sorted(found)


def _refused(path: Path, name: str) -> Submission | None:
    links = _links(path)
    if not links:
        return None
    shown = ", ".join(str(p) for p in links[:3]) + (" ..." if len(links) > 3 else "")
    return Submission(
        name, path, None, (), f"{shown}: a symbolic link; hand in the file itself, not a link to it"
    )


def _file(path: Path, name: str) -> Submission:
    return _refused(path, name) or Submission(name, path, path, (path,))


def _folder(path: Path, name: str, entry_name: str) -> Submission:
    refused = _refused(path, name)
    if refused is not None:
        return refused
    files = tuple(_python_files(path))
    entry = path / entry_name
    if entry.is_file():
        return Submission(name, path, entry, files)
    top = sorted(p for p in path.glob("*.py"))
    if len(top) == 1:
        return Submission(name, path, top[0], files)
    if not top:
        return Submission(name, path, None, files, f"no Python program (.py file) in {path}")
    listed = ", ".join(p.name for p in top)
    return Submission(
        name,
        path,
        None,
        files,
        f"several programs ({listed}) in {path} and none is named {entry_name}; rename the one to run",
    )


def find_submissions(paths: list[str | Path], entry_name: str = DEFAULT_ENTRY) -> list[Submission]:
    """The submissions among the given files and folders (see the module docstring), in the order given."""
    found: list[Submission] = []
    for given in paths:
        path = Path(given)
        name = str(given)
        if path.is_file():
            found.append(_file(path, name))
        elif path.is_dir():
            if (path / entry_name).is_file():
                found.append(_folder(path, name, entry_name))
                continue
            children = sorted(
                p for p in path.iterdir() if not p.name.startswith((".", "_")) and p.name not in SKIPPED
            )
            before = len(found)
            for child in children:
                child_name = str(Path(name) / child.name)
                if child.is_file() and child.suffix == ".py":
                    found.append(_file(child, child_name))
                elif child.is_dir():
                    found.append(_folder(child, child_name, entry_name))
            if len(found) == before:
                found.append(Submission(name, path, None, (), f"no Python program (.py file) in {path}"))
        else:
            found.append(Submission(name, path, None, (), f"{path}: no such file or folder"))
    return found
