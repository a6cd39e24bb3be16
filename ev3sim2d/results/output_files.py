"""Writing and reading files in folders someone else may have prepared: never through a planted name.

A grader runs in a student's checkout, a teacher saves a world into a shared class folder: whoever can
write there can plant a symbolic link (or a FIFO, a socket, /dev/zero) at the name a writer uses, and
a writer that opens that name writes where the link points, as the writer's user.  So every output of
ev3sim2d is written into a new file that `mkstemp` creates (O_CREAT | O_EXCL: no link can be there,
and its name cannot be guessed) in the target's own folder, flushed to disk, and renamed over the
target: a link planted at the target's name is replaced, never followed.  A file that an output is
appended to (GitHub's $GITHUB_OUTPUT) is opened with O_NOFOLLOW where the system has it and must be a
regular file; a file read back (a worker's result) is opened the same way and read up to a limit.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path

_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)  # (so that opening a FIFO planted at the name does not wait)
_CLOEXEC = getattr(os, "O_CLOEXEC", 0)
_BINARY = getattr(os, "O_BINARY", 0)


class PlantedFile(OSError):
    """A name that should be a regular file is something else (a link, a FIFO, a device, a folder)."""


def write_file(path: str | Path, data: bytes | str, encoding: str = "utf-8", mode: int | None = None) -> None:
    """Write `data` at `path` as a new file that replaces whatever had the name (a link included, which
    is replaced, not followed).  mode: the file's permission bits (default: those of the file it
    replaces when that is a regular file, else 0o644 as the umask allows)."""
    target = Path(path)
    payload = data.encode(encoding) if isinstance(data, str) else data
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(payload)
        _finish(Path(name), target, mode)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(name)
        raise


@contextlib.contextmanager
def writing(path: str | Path, mode: int | None = None) -> Iterator[Path]:
    """The name of a new, empty file in path's folder to write (by a library that wants a name: PyAV,
    OpenCV, numpy); when the block ends without an error it is flushed and renamed to path; else it is
    removed and path is left as it was."""
    target = Path(path)
    folder = target.parent
    # (ends as the target does: a library may pick the format by the name's ending)
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=f".part{target.suffix}", dir=folder)
    temporary = Path(name)
    try:
        os.close(fd)
        yield temporary
        _finish(temporary, target, mode)
    except BaseException:
        with contextlib.suppress(OSError):
            temporary.unlink()
        raise


def _finish(temporary: Path, target: Path, mode: int | None) -> None:
    if mode is None:
        try:
            info = os.lstat(target)
            mode = stat.S_IMODE(info.st_mode) if stat.S_ISREG(info.st_mode) else None
        except OSError:
            mode = None
    if mode is None:
        umask = os.umask(0)
        os.umask(umask)
        mode = 0o644 & ~umask
    os.chmod(temporary, mode)
    fd = os.open(temporary, os.O_RDONLY | _BINARY)
    try:
        os.fsync(fd)
    except OSError:
        pass  # (a system or file system that cannot sync a file opened for reading)
    finally:
        os.close(fd)
    os.replace(temporary, target)


def replace_keeping_backup(path: str | Path, text: str, limit: int = 16 * 2**20) -> None:
    """Write a file the user edits (a world, a robot) with its new text, keeping the old one as PATH.bak;
    the old one is read without following a link (PlantedFile when it is not a regular file, and then
    nothing is written) and up to `limit` bytes."""
    target = Path(path)
    try:
        old = read_limited(target, limit + 1)
    except FileNotFoundError:
        old = None
    if old is not None:
        if len(old) > limit:
            raise PlantedFile(f"{target}: over {limit} bytes: not a file this writes over")
        write_file(target.with_name(target.name + ".bak"), old)
    write_file(target, text)


def make_folder(path: str | Path) -> Path:
    """The folder at path, made (with its parents) if missing; refused when something that is not a
    folder, or a link to one, is there (its files would land where the link points)."""
    folder = Path(path)
    folder.mkdir(parents=True, exist_ok=True)
    if not stat.S_ISDIR(os.lstat(folder).st_mode):
        raise PlantedFile(f"{folder}: not a folder of its own (a link or a file is there): refused")
    return folder


def make_folder_in(base: str | Path, relative: str | Path) -> Path:
    """The folder base/relative (e.g. a project's .idea/runConfigurations), made part by part; refused when
    a part is a link or not a folder, wherever it is (a link at `.idea` would put the files where it
    points, though the last part is a real folder there)."""
    folder = Path(base)
    for part in Path(relative).parts:
        folder = folder / part
        try:
            os.mkdir(folder)
        except FileExistsError:
            pass
        if not stat.S_ISDIR(os.lstat(folder).st_mode):
            raise PlantedFile(f"{folder}: not a folder of its own (a link or a file is there): refused")
    return folder


def append_text(path: str | Path, text: str) -> None:
    """Append text to an existing or new regular file at path, never through a link there."""
    fd = os.open(
        path, os.O_WRONLY | os.O_APPEND | os.O_CREAT | _NOFOLLOW | _NONBLOCK | _CLOEXEC | _BINARY, 0o644
    )
    try:
        _regular(fd, path)
        os.write(fd, text.encode("utf-8"))
    finally:
        os.close(fd)


def read_limited(path: str | Path, limit: int) -> bytes:
    """At most `limit` bytes from the start of the regular file at path, never through a link (a link,
    a FIFO or a device planted at the name is refused: PlantedFile)."""
    try:
        fd = os.open(path, os.O_RDONLY | _NOFOLLOW | _NONBLOCK | _CLOEXEC | _BINARY)
    except OSError as err:
        if err.errno == errno.ELOOP or (err.errno == errno.EMLINK and os.path.islink(path)):  # (O_NOFOLLOW)
            raise PlantedFile(f"{path}: a link (something was put at this name): refused") from None
        raise
    try:
        _regular(fd, path)
        chunks, left = [], limit
        while left > 0:
            chunk = os.read(fd, min(left, 1 << 20))
            if not chunk:
                break
            chunks.append(chunk)
            left -= len(chunk)
        return b"".join(chunks)
    finally:
        os.close(fd)


def _regular(fd: int, path) -> None:
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        raise PlantedFile(f"{path}: not a regular file (something was put at this name): refused")
