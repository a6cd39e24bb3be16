#!/usr/bin/env python3
"""Is the live page smooth with 4 robots, and does it slow the simulation?  (`ev3sim2d live`, issue 14)

Four sumo programs (examples/sumo.py) in mazes/sumo-4.yaml (46 x 46 cells of 4 cm: more cells than the
issue's 20 x 20 world) run live, and the page is opened in headless Debian Chromium (playwright, as the
browser tests do: tests/headless_chromium.py).  Measured, each over --seconds of wall time:

(a) the simulation's speed (simulated seconds per wall second) as fast as it goes, no page open;
(b) the same with the page open, and the page's frames: requestAnimationFrame callbacks per second
    (fps), the 95th percentile of the time between two frames, and of the time the page's own drawing
    of one frame takes (window.ev3live.frames());
(c) the page at real time (speed 1): fps and frame times, and how well the simulation keeps real time.

The simulation never waits for the page (the page reads the state the run publishes), so (a) and (b)
should be the same but for the CPU the browser takes from a shared machine.
Run:  python benchmarks/live_page.py [--seconds 5]
"""

from __future__ import annotations

import argparse
import statistics
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ev3sim2d.live.engine import LiveRun  # noqa: E402
from ev3sim2d.live.server import LiveServer, LiveWorldFile  # noqa: E402
from ev3sim2d.world.maze_file import load_maze  # noqa: E402
from tests.headless_chromium import ARGS, executable  # noqa: E402

WORLD = ROOT / "mazes" / "sumo-4.yaml"
PROGRAM = ROOT / "examples" / "sumo.py"

RECORD_FRAMES = """() => {
  window.__stamps = [];
  const tick = (t) => { window.__stamps.push(t); requestAnimationFrame(tick); };
  requestAnimationFrame(tick);
}"""


def sim_speed(live: LiveRun, seconds: float) -> float:
    """Simulated seconds per wall second, over `seconds` of wall time."""
    t0, w0 = live.state()["t_s"], time.perf_counter()
    time.sleep(seconds)
    return (live.state()["t_s"] - t0) / (time.perf_counter() - w0)


def p95(values: list[float]) -> float:
    return statistics.quantiles(values, n=20)[-1] if len(values) > 1 else float("nan")


def page_frames(page, live: LiveRun, seconds: float) -> dict:
    """fps, the frame interval's p95 and the drawing's p95 over `seconds`, and the simulation's speed."""
    page.evaluate(RECORD_FRAMES)
    page.wait_for_timeout(300)
    page.evaluate("window.__stamps = []")
    before = page.evaluate("ev3live.frames()")
    speed = sim_speed(live, seconds)
    stamps = page.evaluate("window.__stamps")
    after = page.evaluate("ev3live.frames()")
    intervals = [b - a for a, b in zip(stamps, stamps[1:], strict=False)]
    drawn = after["count"] - before["count"]
    draws = after["drawMs"][-drawn:] if drawn else []
    return {
        "fps": len(intervals) / (sum(intervals) / 1000) if intervals else 0.0,
        "frame_p95_ms": p95(intervals),
        "draw_mean_ms": statistics.fmean(draws) if draws else float("nan"),
        "draw_p95_ms": p95(draws),
        "sim_speed": speed,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=5.0)
    args = parser.parse_args()
    chromium = executable()
    if chromium is None:
        print("no Chromium found (apt-get install chromium)")
        return 1
    from playwright.sync_api import sync_playwright

    live = LiveRun([PROGRAM] * 4, load_maze(WORLD), speed=None, watch=False)
    server = LiveServer(live, LiveWorldFile(WORLD))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    live.start()
    try:
        while live.state()["status"] != "running" or live.state()["t_s"] < 0.5:
            time.sleep(0.05)
        alone = sim_speed(live, args.seconds)
        print(f"(a) as fast as it goes, no page:   {alone:7.1f} x real time")
        with sync_playwright() as p:
            browser = p.chromium.launch(executable_path=chromium, args=ARGS)
            page = browser.new_page(viewport={"width": 1280, "height": 800}, bypass_csp=True)
            page.goto(server.url)
            page.wait_for_function("window.ev3live && window.ev3live.ready()")
            fast = page_frames(page, live, args.seconds)
            print(f"(b) as fast as it goes, page open: {fast['sim_speed']:7.1f} x real time")
            print(
                f"    page: {fast['fps']:.1f} fps, frame interval p95 {fast['frame_p95_ms']:.1f} ms, "
                f"drawing a frame {fast['draw_mean_ms']:.2f} ms mean / {fast['draw_p95_ms']:.2f} ms p95"
            )
            live.set_speed(1.0)
            real = page_frames(page, live, args.seconds)
            print(f"(c) real time, page open:          {real['sim_speed']:7.3f} x real time")
            print(
                f"    page: {real['fps']:.1f} fps, frame interval p95 {real['frame_p95_ms']:.1f} ms, "
                f"drawing a frame {real['draw_mean_ms']:.2f} ms mean / {real['draw_p95_ms']:.2f} ms p95"
            )
            browser.close()
    finally:
        server.shutdown()
        server.server_close()
        live.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
