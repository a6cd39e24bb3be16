"""The MP4 plays in a browser: headless Chromium loads it in a page, reports its duration and plays it.

Debian's `chromium` (driven by playwright, never `playwright install`) plays H.264.  Should a build
not, the test says so and checks the same with a VP9 WebM of the same frames instead.  Without
Chromium the test is skipped, except in CI (CI=true), where .ci/run installs it and it must run.
"""

import functools
import http.server
import threading
from fractions import Fraction
from pathlib import Path

import av
import pytest

from ev3sim2d.render.video import VideoOptions, write_video
from tests.headless_chromium import chromium

PAGE = """<!doctype html>
<html><body>
<video id="v" muted playsinline preload="auto" src="%s" width="640" height="360"></video>
</body></html>
"""


def _serve(folder: Path):
    """A web server for `folder` on 127.0.0.1 (any free port), in a thread; stop with .shutdown()."""

    class Quiet(http.server.SimpleHTTPRequestHandler):
        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(
        ("127.0.0.1", 0), functools.partial(Quiet, directory=str(folder))
    )
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def _webm_copy(mp4: Path, webm: Path) -> None:
    """The same frames as VP9 in WebM, for a Chromium without H.264."""
    with av.open(str(mp4)) as source, av.open(str(webm), "w") as target:
        video = source.streams.video[0]
        stream = target.add_stream("libvpx-vp9", rate=video.average_rate)
        stream.width, stream.height, stream.pix_fmt = video.width, video.height, "yuv420p"
        for index, frame in enumerate(source.decode(video)):
            frame.pts, frame.time_base = index, 1 / Fraction(video.average_rate)
            target.mux(stream.encode(frame))
        target.mux(stream.encode(None))


def test_the_video_loads_and_plays_in_chromium(driving_trace, tmp_path):
    options = VideoOptions(fps=30, size=(640, 360))
    frames = write_video(driving_trace, tmp_path / "run.mp4", options, progress=False)
    expected_s = frames / options.fps
    server = _serve(tmp_path)
    try:
        with chromium() as browser:
            page = browser.new_page()
            base = f"http://127.0.0.1:{server.server_address[1]}"
            h264 = page.evaluate(
                "document.createElement('video').canPlayType('video/mp4; codecs=\"avc1.64001f\"')"
            )
            name = "run.mp4"
            if not h264:
                print("this Chromium does not play H.264: checking a VP9 WebM of the same frames instead")
                _webm_copy(tmp_path / "run.mp4", tmp_path / "run.webm")
                name = "run.webm"
            (tmp_path / "page.html").write_text(PAGE % name)
            page.goto(f"{base}/page.html")
            page.wait_for_function("document.getElementById('v').readyState >= 2", timeout=15000)
            info = page.evaluate(
                "(() => { const v = document.getElementById('v');"
                " return {duration: v.duration, width: v.videoWidth, height: v.videoHeight, error: v.error}; })()"
            )
            assert info["error"] is None
            assert (info["width"], info["height"]) == (640, 360)
            assert info["duration"] == pytest.approx(expected_s, abs=0.1)
            page.evaluate("document.getElementById('v').play()")
            page.wait_for_function("document.getElementById('v').currentTime > 0.5", timeout=15000)
            assert page.evaluate("document.getElementById('v').error") is None
    finally:
        server.shutdown()
