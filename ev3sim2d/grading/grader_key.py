"""The grader's own key: a result is taken again (`grade --resume`) only if this grader signed it.

A grader often runs in a folder a student controls (a GitHub Classroom checkout): a results file
committed there must not count as grading.  So each submission's result in a results file carries an
HMAC-SHA256 made with a key kept outside any folder being graded: a random key in this user's state
folder ($LOCALAPPDATA on Windows, else $XDG_STATE_HOME or ~/.local/state; EV3SIM2D_STATE_DIR to put
it elsewhere), made on first use, readable by this user only.  A result whose signature does not
verify, or a file from another machine, is graded again.
"""

from __future__ import annotations

import hashlib
import hmac
import json
import os
import secrets
from pathlib import Path

from ..results.output_files import PlantedFile, read_limited

KEY_FILE = "grader.key"
KEY_BYTES = 32
_NOFOLLOW = getattr(os, "O_NOFOLLOW", 0)


def state_folder() -> Path:
    """Where this user's ev3sim2d keeps what must outlive a run and stay out of graded folders."""
    chosen = os.environ.get("EV3SIM2D_STATE_DIR")
    if chosen:
        return Path(chosen)
    base = os.environ.get("LOCALAPPDATA") or os.environ.get("XDG_STATE_HOME")
    return (Path(base) if base else Path.home() / ".local" / "state") / "ev3sim2d"


def grader_key() -> bytes | None:
    """The key (made now if there is none yet), or None where none can be kept (results are then
    never taken again)."""
    path = state_folder() / KEY_FILE
    try:
        return _read_key(path)
    except FileNotFoundError:
        pass
    except (OSError, PlantedFile, ValueError):
        return None
    try:
        path.parent.mkdir(parents=True, exist_ok=True, mode=0o700)
        fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | _NOFOLLOW, 0o600)
        with os.fdopen(fd, "wb") as handle:
            handle.write(secrets.token_bytes(KEY_BYTES))
        return _read_key(path)
    except FileExistsError:  # another grader made it just now
        try:
            return _read_key(path)
        except (OSError, ValueError):
            return None
    except (OSError, ValueError):
        return None


def _read_key(path: Path) -> bytes:
    key = read_limited(path, KEY_BYTES + 1)
    if len(key) != KEY_BYTES:
        raise ValueError(f"{path}: not a key of {KEY_BYTES} bytes")
    return key


def signature(key: bytes, lesson_id: str, item: dict) -> str:
    """The HMAC of one submission's result (its dict in the results file, without a signature)."""
    payload = json.dumps([lesson_id, {k: v for k, v in item.items() if k != "signature"}], sort_keys=True)
    return hmac.new(key, payload.encode("utf-8"), hashlib.sha256).hexdigest()


def signed_by_this_grader(key: bytes, lesson_id: str, item: dict) -> bool:
    given = item.get("signature")
    return type(given) is str and hmac.compare_digest(given, signature(key, lesson_id, item))
