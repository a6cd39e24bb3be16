"""Videos and frame sequences of a run.

The video is H.264 in an MP4 (yuv420p, the moov atom first), the one format
that Chrome, Firefox and Safari all play, encoded with PyAV's bundled FFmpeg
and libx264.  Frame k shows simulated time k·speed/fps; the video has
1 + ⌈sim time · fps / speed⌉ frames, the last one showing the end of the run.

Drawing and encoding overlap: the main thread draws while a second thread
converts each frame to YUV and hands it to x264 (both release the GIL), and
x264 runs its own threads.
"""

from __future__ import annotations

import math
import queue
import threading
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import av
import cv2
import numpy as np

from ..results.output_files import make_folder, writing
from ..results.trace import Trace
from .audio import SAMPLE_RATE, sound_track
from .frame import FrameRenderer, save_png
from .layout import DEFAULT_SIZE
from .progress import Progress

# x264: the ultrafast preset, given back the three tools that matter for these pictures (flat colours,
# sharp text, most of the frame still from one frame to the next): CABAC, the macroblock tree over a
# short look-ahead, and adaptive quantisation.  About 4 ms of one core per 1280x720 frame, where
# `veryfast` takes 7 ms, at a fifth more bytes (see docs/rendering.md).
X264_OPTIONS = {
    "preset": "ultrafast",
    "crf": "23",
    "x264-params": "cabac=1:rc-lookahead=10:mbtree=1:aq-mode=1",
}
# cv2's BGR->I420 is BT.601 limited range: say so in the stream, or players may assume BT.709
X264_COLOR = "colorprim=smpte170m:transfer=smpte170m:colormatrix=smpte170m:range=tv"
KEYFRAME_EVERY_S = 5  # a seek in the browser decodes at most this much video
AUDIO_FRAME = 1024  # samples per AAC frame
QUEUE_FRAMES = 6


@dataclass(frozen=True)
class VideoOptions:
    fps: float = 30.0
    speed: float = 1.0
    size: tuple[int, int] = DEFAULT_SIZE
    audio: bool = True


def frame_times(end_s: float, fps: float, speed: float) -> np.ndarray:
    """The simulated time each video frame shows: k·speed/fps, up to and including the end."""
    count = math.ceil(end_s * fps / speed - 1e-9) + 1
    return np.minimum(np.arange(count) * speed / fps, end_s)


def write_video(
    trace: Trace, path: str | Path, options: VideoOptions = VideoOptions(), progress: bool = True
) -> int:
    """Write the run as an MP4 video; returns the number of frames."""
    width, height = options.size
    if width % 2 or height % 2:
        raise ValueError(f"a video's width and height must be even, got {width}x{height}")
    renderer = FrameRenderer(trace, options.size, options.speed)
    times = frame_times(renderer.timeline.end_s, options.fps, options.speed)
    rate = Fraction(options.fps).limit_denominator(1001)
    length_s = len(times) / options.fps
    samples = sound_track(renderer.timeline.sounds, length_s, options.speed) if options.audio else None

    with writing(path) as temporary:
        return _encode(temporary, path, renderer, times, rate, samples, options, progress)


def _encode(temporary, path, renderer, times, rate, samples, options, progress) -> int:
    width, height = options.size
    container = av.open(str(temporary), mode="w", format="mp4", options={"movflags": "+faststart"})
    try:
        video = container.add_stream("libx264", rate=rate)
        video.width, video.height, video.pix_fmt = width, height, "yuv420p"
        video.codec_context.thread_type = "FRAME"  # x264's frame threads: PyAV's default (slices) is slower
        params = (
            X264_OPTIONS["x264-params"]
            + ":"
            + X264_COLOR
            + f":keyint={max(1, int(round(options.fps * KEYFRAME_EVERY_S)))}"
        )
        video.options = {**X264_OPTIONS, "x264-params": params}
        audio = None
        if samples is not None:
            audio = container.add_stream("aac", rate=SAMPLE_RATE)
            audio.layout = "mono"
        encoder = _Encoder(container, video, audio, samples, options.fps)
        bar = Progress(len(times), f"writing {Path(path).name}") if progress else None
        encoder.start()
        # frames are drawn into a ring of buffers: a buffer comes round again only after the encoder
        # has converted it (the queue holds QUEUE_FRAMES, the encoder one more)
        buffers = [np.empty((height, width, 3), dtype=np.uint8) for _ in range(QUEUE_FRAMES + 3)]
        try:
            for k, t in enumerate(times):
                encoder.put(renderer.frame_at(float(t), buffers[k % len(buffers)]))
                if bar is not None:
                    bar.update(k + 1)
        finally:
            encoder.finish()
            if bar is not None:
                bar.close()
    finally:
        container.close()
    return len(times)


class _Encoder(threading.Thread):
    """Takes drawn frames from a queue, converts and encodes them, and keeps the audio in step."""

    def __init__(self, container, video, audio, samples: np.ndarray | None, fps: float) -> None:
        super().__init__(name="ev3sim2d-encoder", daemon=True)
        self.container, self.video, self.audio, self.samples, self.fps = container, video, audio, samples, fps
        self.frames: queue.Queue = queue.Queue(maxsize=QUEUE_FRAMES)
        self.error: BaseException | None = None
        self._count = 0
        self._audio_done = 0

    def put(self, frame: np.ndarray) -> None:
        if self.error is not None:
            raise self.error
        self.frames.put(frame)

    def finish(self) -> None:
        self.frames.put(None)
        self.join()
        if self.error is not None:
            raise self.error

    def run(self) -> None:
        try:
            while (frame := self.frames.get()) is not None:
                yuv = cv2.cvtColor(frame, cv2.COLOR_BGR2YUV_I420)
                picture = av.VideoFrame.from_ndarray(yuv, format="yuv420p")
                picture.pts = self._count
                self._count += 1
                self.container.mux(self.video.encode(picture))
                self._audio_until(self._count / self.fps)
            self.container.mux(self.video.encode(None))
            self._audio_until(math.inf)
            if self.audio is not None:
                self.container.mux(self.audio.encode(None))
        except BaseException as err:  # noqa: BLE001  (handed to the drawing thread)
            self.error = err
            while self.frames.get() is not None:  # let the drawing thread finish its puts
                pass

    def _audio_until(self, t_s: float) -> None:
        """Encode the sound track up to video time t_s, in whole AAC frames."""
        if self.audio is None or self.samples is None:
            return
        end = len(self.samples) if math.isinf(t_s) else min(int(t_s * SAMPLE_RATE), len(self.samples))
        while self._audio_done + AUDIO_FRAME <= end or (math.isinf(t_s) and self._audio_done < end):
            chunk = self.samples[self._audio_done : self._audio_done + AUDIO_FRAME]
            frame = av.AudioFrame.from_ndarray(chunk.reshape(1, -1), format="fltp", layout="mono")
            frame.sample_rate = SAMPLE_RATE
            frame.pts = self._audio_done
            self._audio_done += len(chunk)
            self.container.mux(self.audio.encode(frame))


def write_frames(
    trace: Trace,
    folder: str | Path,
    every: int = 1,
    options: VideoOptions = VideoOptions(),
    progress: bool = True,
) -> int:
    """Every `every`-th frame of the video as folder/frame-NNNNNN.png (N: the video frame); returns how many."""
    folder = make_folder(folder)
    renderer = FrameRenderer(trace, options.size, options.speed)
    times = frame_times(renderer.timeline.end_s, options.fps, options.speed)
    picked = range(0, len(times), max(1, every))
    bar = Progress(len(picked), f"writing {folder.name}/") if progress else None
    for done, k in enumerate(picked, start=1):
        save_png(renderer.frame_at(float(times[k])), folder / f"frame-{k:06d}.png")
        if bar is not None:
            bar.update(done)
    if bar is not None:
        bar.close()
    return len(picked)
