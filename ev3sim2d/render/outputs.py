"""The picture options that `run` and `render` share (--video, --frames, --fps, ...), and writing them.

OpenCV and PyAV are imported only to write pictures: every command's parser is built from this
module, and a class run forks workers from a process that should not carry them."""

from __future__ import annotations

import argparse
import re

from ..results.trace import Trace
from .layout import DEFAULT_SIZE

MAX_FPS = 120.0


def frame_size(text: str) -> tuple[int, int]:
    """'1280x720' -> (1280, 720); both even (H.264 in yuv420p needs that) and at least 320x180."""
    match = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", text)
    if not match:
        raise argparse.ArgumentTypeError(f"{text!r} is not a frame size; write WIDTHxHEIGHT, e.g. 1280x720")
    width, height = int(match.group(1)), int(match.group(2))
    if width < 320 or height < 180 or width > 7680 or height > 4320:
        raise argparse.ArgumentTypeError(f"{text!r}: frames are 320x180 to 7680x4320 pixels")
    if width % 2 or height % 2:
        raise argparse.ArgumentTypeError(
            f"{text!r}: width and height must be even, e.g. {width + width % 2}x{height + height % 2}"
        )
    return width, height


def _positive(name: str, most: float | None = None):
    def parse(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not value > 0 or (most is not None and value > most):
            limit = f" and at most {most:g}" if most is not None else ""
            raise argparse.ArgumentTypeError(f"{name} must be more than 0{limit}, got {text!r}")
        return value

    return parse


def _whole(text: str) -> int:
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError(f"--every takes a whole number of frames, 1 or more, got {text!r}")
    return int(text)


def add_picture_arguments(parser: argparse.ArgumentParser) -> None:
    """--video, --frames, --every, --fps, --speed, --size, --audio/--no-audio (not --png: each command says its own)."""
    parser.add_argument(
        "--video", metavar="FILE", help="write a video of the run (H.264 MP4; plays in any browser)"
    )
    parser.add_argument("--frames", metavar="DIR", help="write the video's frames as PNG files into DIR")
    parser.add_argument(
        "--every",
        type=_whole,
        default=1,
        metavar="N",
        help="with --frames, keep every N-th frame (default: 1)",
    )
    parser.add_argument(
        "--fps", type=_positive("--fps", MAX_FPS), default=30.0, help="video frames per second (default: 30)"
    )
    parser.add_argument(
        "--speed",
        type=_positive("--speed"),
        default=1.0,
        metavar="X",
        help="play the run X times faster than it ran (default: 1; the video lasts sim time / X)",
    )
    parser.add_argument(
        "--size",
        type=frame_size,
        default=DEFAULT_SIZE,
        metavar="WxH",
        help="frame size in pixels, for --video, --frames and --png (default: 1280x720)",
    )
    parser.add_argument(
        "--audio",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="give the video a sound track of the robot's beeps and tones (default: on when it made any)",
    )


def write_pictures(trace: Trace, args: argparse.Namespace) -> None:
    """Whatever pictures the arguments ask for: --png, --video, --frames."""
    from .frame import write_png
    from .video import VideoOptions, write_frames, write_video

    options = VideoOptions(fps=args.fps, speed=args.speed, size=args.size, audio=args.audio)
    if getattr(args, "png", None):
        write_png(trace, args.png, args.size)
    if args.video:
        write_video(trace, args.video, options)
    if args.frames:
        write_frames(trace, args.frames, args.every, options)
