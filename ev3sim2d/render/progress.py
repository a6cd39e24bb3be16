"""A one-line progress bar on standard error, shown only when that is a terminal."""

from __future__ import annotations

import sys
import time
from typing import TextIO

BAR_CHARS = 30
REDRAW_EVERY_S = 0.1


class Progress:
    """`update(done)` as work goes on, `close()` at the end; silent unless the stream is a terminal."""

    def __init__(self, total: int, label: str, stream: TextIO | None = None) -> None:
        self.total = max(total, 1)
        self.label = label
        self.stream = stream if stream is not None else sys.stderr
        self.enabled = bool(getattr(self.stream, "isatty", lambda: False)())
        self.started = time.monotonic()
        self._shown_at = 0.0

    def update(self, done: int) -> None:
        if not self.enabled:
            return
        now = time.monotonic()
        if now - self._shown_at < REDRAW_EVERY_S and done < self.total:
            return
        self._shown_at = now
        share = min(done / self.total, 1.0)
        filled = int(share * BAR_CHARS)
        elapsed = now - self.started
        left = elapsed / share - elapsed if share > 0 else 0.0
        self.stream.write(
            f"\r{self.label} [{'#' * filled}{'.' * (BAR_CHARS - filled)}] {share * 100:3.0f}% "
            f"{done}/{self.total} frames, {left:4.1f} s left "
        )
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            self.update(self.total)
            self.stream.write("\n")
            self.stream.flush()
