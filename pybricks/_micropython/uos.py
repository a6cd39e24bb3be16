"""MicroPython's `uos` (unix port): files and folders, with CPython's os doing the work."""

from os import chdir, getcwd, getenv, listdir, mkdir, remove, rename, rmdir, sep, stat, statvfs, system  # noqa: F401
from os import scandir as _scandir


def ilistdir(path="."):
    """(name, type, inode) for each entry of `path`: type 0x4000 for a folder, 0x8000 for a file."""
    for entry in _scandir(path):
        kind = 0x4000 if entry.is_dir(follow_symlinks=False) else 0x8000
        yield (entry.name, kind, entry.inode())
