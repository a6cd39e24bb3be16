"""`--videos DIR`: keep what happened in each failed variant, to watch: an MP4 when the renderer can make one.

Files go to DIR/<submission>/<variant>.mp4 (the submission's file or folder name, without .py).  Without a video writer in
ev3sim2d.render, the trace itself (`.npz`, for `Trace.load`) and a picture of
the end of the run (`.png`) are written instead.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import re
from collections.abc import Callable
from pathlib import Path

from ..results.output_files import make_folder
from ..results.trace import Trace

VIDEO_MODULE = "ev3sim2d.render.video"
VIDEO_FUNCTIONS = ("write_video", "write_mp4")


def video_writer() -> Callable | None:
    """The renderer's `write_video(trace, path)`, if there is one (quiet: no progress bar)."""
    try:
        module = importlib.import_module(VIDEO_MODULE)
    except ImportError:
        return None
    for name in VIDEO_FUNCTIONS:
        function = getattr(module, name, None)
        if callable(function):
            if "progress" in inspect.signature(function).parameters:
                return functools.partial(function, progress=False)
            return function
    return None


def folder_name(submission: str) -> str:
    """A submission's own name as a safe folder name: 'class/alice.py' -> 'alice', 'class/bob/' -> 'bob'."""
    last = Path(submission).name
    stem = last[:-3] if last.endswith(".py") else last
    name = re.sub(r"[^A-Za-z0-9._-]+", "_", stem).strip("._")
    return name or "submission"


def keep_failed_run(folder: Path, submission: str, variant: str, trace_path: Path) -> list[Path]:
    """Write the video (or trace and picture) of one failed run; the paths written."""
    target = make_folder(folder / folder_name(submission))
    writer = video_writer()
    if writer is not None:
        path = target / f"{variant}.mp4"
        writer(Trace.load(trace_path), path)
        return [path]
    from ..render.frame import write_png

    kept = target / f"{variant}.npz"
    trace = Trace.load(trace_path)
    trace.save(kept)
    picture = target / f"{variant}.png"
    write_png(trace, picture)
    return [kept, picture]
