"""A brick's scratch folder, which the program owns: the simulator never trusts a name in it.

The program may replace anything in its folder while it runs: its console file by a link to
/proc/self/environ or /dev/zero, a folder by a link elsewhere, or build a tree thousands of folders
deep.  So the simulator opens the console itself before the brick starts and reads it only through
that descriptor, and only its last bytes; and it removes a scratch folder (or a grading job's folder,
which holds one) through folder descriptors, one level at a time: no path grows too long, no link is
followed, no recursion runs out, and a folder the program made unreadable is made readable again
first.  Where the system has no descriptor-relative calls (Windows), it goes by paths, as deep as the
system lets a path be, still without recursion and without following links.
"""

from __future__ import annotations

import contextlib
import os
import stat
from pathlib import Path

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_DIRECTORY = getattr(os, "O_DIRECTORY", 0)
_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)
_BINARY = getattr(os, "O_BINARY", 0)
_BY_DESCRIPTOR = {os.open, os.unlink, os.rmdir} <= os.supports_dir_fd and os.scandir in os.supports_fd


def open_console(path: Path) -> int:
    """A new console file for a brick (its fds 1 and 2), opened here, read and write: created, never
    found (O_EXCL), so nothing planted at the name is used."""
    return os.open(path, os.O_RDWR | os.O_CREAT | os.O_EXCL | _NOFOLLOW | _CLOEXEC | _BINARY, 0o600)


def tail(source: int | Path, keep_bytes: int) -> str:
    """The last keep_bytes of a console: from a descriptor opened before the program ran, or from a
    path opened without following a link and only if it is a regular file ("" otherwise)."""
    if isinstance(source, int):
        return _tail_of(source, keep_bytes)
    try:
        fd = os.open(source, os.O_RDONLY | _NOFOLLOW | _NONBLOCK | _CLOEXEC | _BINARY)
    except OSError:
        return ""
    try:
        return _tail_of(fd, keep_bytes)
    finally:
        os.close(fd)


def _tail_of(fd: int, keep_bytes: int) -> str:
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            return ""
        start = max(0, info.st_size - keep_bytes)
        os.lseek(fd, start, os.SEEK_SET)
        data = os.read(fd, keep_bytes)
    except OSError:
        return ""
    return data.decode("utf-8", "replace").strip()


def remove_tree(path: str | Path) -> None:
    """Remove a folder and everything in it, whatever shape the program gave it (see the module's
    docstring); a link at `path` itself is removed, not followed.  What cannot be removed is left."""
    path = Path(path)
    with contextlib.suppress(OSError):
        if _BY_DESCRIPTOR:
            _remove_by_descriptors(path)
        else:
            _remove_by_paths(path)


def _remove_by_descriptors(path: Path) -> None:
    top = os.open(path.parent, os.O_RDONLY | _DIRECTORY | _CLOEXEC)
    current = None
    try:
        try:
            if not _is_folder(path.name, top):
                os.unlink(path.name, dir_fd=top)
                return
            current = _open_folder(path.name, top)
        except FileNotFoundError:
            return
        names = [path.name]  # the folders from the top down to the one `current` holds
        while names:
            child = _first_folder_emptying(current)
            if child is not None:
                inner = _open_folder(child, current)
                os.close(current)
                current = inner
                names.append(child)
                continue
            up = (
                top if len(names) == 1 else os.open("..", os.O_RDONLY | _DIRECTORY | _CLOEXEC, dir_fd=current)
            )
            os.close(current)
            current = None if up is top else up
            os.rmdir(names.pop(), dir_fd=up)
    finally:
        if current is not None:
            os.close(current)
        os.close(top)


def _first_folder_emptying(fd: int) -> str | None:
    """Remove every entry of the folder at fd that is not a folder; the name of a folder in it, if any."""
    with os.scandir(fd) as entries:
        for entry in entries:
            if entry.is_dir(follow_symlinks=False):
                return entry.name
            with contextlib.suppress(FileNotFoundError):
                os.unlink(entry.name, dir_fd=fd)
    return None


def _is_folder(name: str, parent: int) -> bool:
    return stat.S_ISDIR(os.lstat(name, dir_fd=parent).st_mode)


def _open_folder(name: str, parent: int) -> int:
    """A descriptor of folder `name` in parent (never a link), made readable first if the program
    made it unreadable."""
    flags = os.O_RDONLY | _DIRECTORY | _NOFOLLOW | _CLOEXEC
    try:
        return os.open(name, flags, dir_fd=parent)
    except PermissionError:
        os.chmod(name, 0o700, dir_fd=parent)
        return os.open(name, flags, dir_fd=parent)


def _remove_by_paths(path: Path) -> None:
    """The same by paths, for a system without descriptor-relative calls: a stack, not recursion."""
    if not path.is_dir() or path.is_symlink():
        path.unlink()
        return
    stack = [(path, False)]
    while stack:
        folder, emptied = stack.pop()
        if emptied:
            with contextlib.suppress(OSError):
                os.rmdir(folder)
            continue
        stack.append((folder, True))
        with contextlib.suppress(OSError), os.scandir(folder) as entries:
            for entry in entries:
                if entry.is_dir(follow_symlinks=False) and not entry.is_symlink():
                    stack.append((Path(entry.path), False))
                else:
                    with contextlib.suppress(OSError):
                        _make_writable(entry.path)
                        os.unlink(entry.path)


def _make_writable(path: str) -> None:
    """(Windows will not remove a read-only file.)"""
    info = os.lstat(path)
    if not info.st_mode & stat.S_IWRITE and not stat.S_ISLNK(info.st_mode):
        os.chmod(path, info.st_mode | stat.S_IWRITE)
