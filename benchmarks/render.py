"""How fast runs become video: frames per second at 1280x720 for drawing alone, encoding alone, and both.

    python benchmarks/render.py [--seconds 20] [--size 1280x720] [--fps 30]

Runs the line follower in the line world (and a wall-bumping program in the
maze, with sounds, LEDs and the LCD) for --seconds of simulated time, then
writes each run's video to a temporary folder.  The figure that matters is
"draw + encode": the whole of `ev3sim2d render --video` after the trace is loaded.
Beside each rate: the CPU time a frame takes (all threads), which does not
depend on how busy the machine's other tenants are, and the cores the machine
gives just now (measured first).
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import sys
import tempfile
import textwrap
import time
from pathlib import Path

import av
import cv2
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from ev3sim2d.render.frame import FrameRenderer  # noqa: E402
from ev3sim2d.render.video import X264_OPTIONS, VideoOptions, frame_times, write_video  # noqa: E402
from ev3sim2d.simulator.run import run_programs  # noqa: E402
from ev3sim2d.world.maze_file import find_maze, load_maze  # noqa: E402

MAZE_PROGRAM = textwrap.dedent(
    """
    from ev3dev2.display import Display
    from ev3dev2.led import Leds
    from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
    from ev3dev2.sensor import INPUT_1, INPUT_4
    from ev3dev2.sensor.lego import TouchSensor, UltrasonicSensor
    from ev3dev2.sound import Sound

    tank, us, touch = MoveTank(OUTPUT_B, OUTPUT_C), UltrasonicSensor(INPUT_4), TouchSensor(INPUT_1)
    sound, leds, lcd = Sound(), Leds(), Display()
    turns = 0
    while True:
        if touch.is_pressed or us.distance_centimeters < 15:
            sound.beep()
            leds.set_color("LEFT", "RED")
            tank.on_for_degrees(-30, 30, 180)
            turns += 1
            print("turn", turns)
            lcd.text_pixels("turns: %d" % turns, x=10, y=10)
            lcd.update()
        else:
            leds.set_color("LEFT", "GREEN")
            tank.on(40, 40)
    """
)


def _trace(program: Path, maze: str, seconds: float):
    return run_programs([program], load_maze(find_maze(maze)), None, seconds, 0, 5.0, None).trace


def _timed(work) -> tuple[float, float]:
    """Wall seconds and CPU seconds (all threads of this process) that `work()` takes."""
    cpu, wall = os.times(), time.perf_counter()
    work()
    after = os.times()
    return time.perf_counter() - wall, (after.user - cpu.user) + (after.system - cpu.system)


def _measure(name: str, trace, size: tuple[int, int], fps: float, folder: Path) -> None:
    renderer = FrameRenderer(trace, size)
    times = frame_times(renderer.timeline.end_s, fps, 1.0)
    n = len(times)
    buffer = np.empty((size[1], size[0], 3), dtype=np.uint8)
    draw_wall, draw_cpu = _timed(lambda: [renderer.frame_at(float(t), buffer) for t in times])

    renderer = FrameRenderer(trace, size)
    yuv = [cv2.cvtColor(renderer.frame_at(float(t), buffer), cv2.COLOR_BGR2YUV_I420) for t in times]
    container = av.open(str(folder / f"{name}-encode-only.mp4"), "w")
    stream = container.add_stream("libx264", rate=int(fps))
    stream.width, stream.height, stream.pix_fmt = size[0], size[1], "yuv420p"
    stream.codec_context.thread_type = "FRAME"
    stream.options = X264_OPTIONS

    def encode() -> None:
        for frame in yuv:
            container.mux(stream.encode(av.VideoFrame.from_ndarray(frame, format="yuv420p")))
        container.mux(stream.encode(None))
        container.close()

    encode_wall, encode_cpu = _timed(encode)
    yuv.clear()

    out = folder / f"{name}.mp4"
    both_wall, both_cpu = _timed(
        lambda: write_video(trace, out, VideoOptions(fps=fps, size=size), progress=False)
    )
    print(
        f"{name:5} {n:5d} frames {size[0]}x{size[1]}: "
        f"draw {n / draw_wall:4.0f} frames/s ({draw_cpu / n * 1000:4.1f} ms CPU a frame), "
        f"encode {n / encode_wall:4.0f} frames/s ({encode_cpu / n * 1000:4.1f} ms), "
        f"draw + encode {n / both_wall:4.0f} frames/s ({both_cpu / n * 1000:4.1f} ms; "
        f"{out.stat().st_size / 1e6:.1f} MB)"
    )


def _spin(_: int) -> float:
    start = time.perf_counter()
    n = 0
    while n < 3_000_000:
        n += 1
    return time.perf_counter() - start


def _cores() -> float:
    """How many cores this machine gives two busy processes right now (2.0 on two idle cores)."""
    alone = _spin(0)
    with multiprocessing.Pool(2) as pool:
        together = max(pool.map(_spin, [0, 1]))
    return 2 * alone / together


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=20.0, help="simulated seconds per run (default 20)")
    parser.add_argument("--size", default="1280x720", help="frame size (default 1280x720)")
    parser.add_argument("--fps", type=float, default=30.0, help="video frame rate (default 30)")
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.lower().split("x"))
    print(f"this machine gives two busy processes {_cores():.1f} cores just now")
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        maze_program = folder / "maze_program.py"
        maze_program.write_text(MAZE_PROGRAM)
        _measure(
            "line",
            _trace(ROOT / "examples" / "line_follower.py", "line", args.seconds),
            size,
            args.fps,
            folder,
        )
        _measure("maze", _trace(maze_program, "maze", args.seconds), size, args.fps, folder)


if __name__ == "__main__":
    main()
