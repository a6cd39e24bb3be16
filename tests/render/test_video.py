"""The MP4, decoded again: H.264 in yuv420p, the promised frame count and size, a robot that moves."""

import math

import av
import numpy as np
import pytest

from ev3sim2d.render.timeline import Timeline
from ev3sim2d.render.video import VideoOptions, frame_times, write_frames, write_video


def decode(path):
    with av.open(str(path)) as container:
        video = container.streams.video[0]
        frames = [f.to_ndarray(format="rgb24") for f in container.decode(video)]
        return (
            video.codec_context.name,
            video.codec_context.pix_fmt,
            frames,
            [s.type for s in container.streams],
        )


def robot_centre(frame_rgb, color_rgb=(230, 170, 30), tolerance=40):
    """Middle of the pixels of the robot's body colour."""
    near = np.all(np.abs(frame_rgb.astype(int) - color_rgb) < tolerance, axis=2)
    ys, xs = np.nonzero(near)
    assert len(xs) > 50, "the robot is not in the frame"
    return xs.mean(), ys.mean()


def test_video_is_h264_yuv420p_with_one_frame_per_step_of_time(driving_trace, tmp_path):
    out = tmp_path / "run.mp4"
    count = write_video(driving_trace, out, VideoOptions(fps=15, size=(640, 360)), progress=False)
    end_s = Timeline(driving_trace).end_s
    assert count == 1 + math.ceil(end_s * 15)
    codec, pix_fmt, frames, streams = decode(out)
    assert (codec, pix_fmt) == ("h264", "yuv420p")
    assert len(frames) == count
    assert frames[0].shape == (360, 640, 3)
    assert "audio" in streams  # it beeped
    x0, y0 = robot_centre(frames[0])
    x1, y1 = robot_centre(frames[-1])
    assert x1 - x0 > 40  # it drove to the right ...
    assert abs(y1 - y0) < 5  # ... straight


def test_speed_2_makes_a_video_half_as_long(driving_trace, tmp_path):
    out = tmp_path / "fast.mp4"
    count = write_video(
        driving_trace, out, VideoOptions(fps=10, speed=2, size=(320, 180), audio=False), progress=False
    )
    assert count == 1 + math.ceil(Timeline(driving_trace).end_s * 10 / 2)
    _, _, frames, streams = decode(out)
    assert len(frames) == count and streams == ["video"]


def test_frames_every_n(driving_trace, tmp_path):
    written = write_frames(
        driving_trace, tmp_path / "frames", every=10, options=VideoOptions(fps=10, size=(320, 180))
    )
    names = sorted(p.name for p in (tmp_path / "frames").iterdir())
    assert len(names) == written and names[:2] == ["frame-000000.png", "frame-000010.png"]


def test_frame_times_end_on_the_end():
    times = frame_times(1.0, 30, 1.0)
    assert len(times) == 31 and times[0] == 0 and times[-1] == pytest.approx(1.0)
    assert list(frame_times(1.0, 10, 4.0)) == pytest.approx(
        [0.0, 0.4, 0.8, 1.0]
    )  # the last frame shows the end
