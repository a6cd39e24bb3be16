"""The picture commands: `run --video/--png`, `render TRACE` (which reads only the trace), their checks."""

import io

import cv2
import numpy as np
import pytest

from ev3sim2d.cli import main
from ev3sim2d.render.outputs import frame_size
from ev3sim2d.render.progress import Progress

PROGRAM = """
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank
MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(40, 20, 1.5)
"""


def test_render_draws_from_the_trace_what_run_drew(tmp_path):
    program = tmp_path / "prog.py"
    program.write_text(PROGRAM)
    ran, trace, rendered = tmp_path / "ran.png", tmp_path / "run.npz", tmp_path / "rendered.png"
    assert (
        main(["run", str(program), "--quiet", "--png", str(ran), "--trace", str(trace), "--size", "640x360"])
        == 0
    )
    assert main(["render", str(trace), "--png", str(rendered), "--size", "640x360"]) == 0
    assert np.array_equal(cv2.imread(str(ran)), cv2.imread(str(rendered)))
    assert main(["render", str(trace), "--video", str(tmp_path / "v.mp4"), "--fps", "5"]) == 0
    assert (tmp_path / "v.mp4").stat().st_size > 1000


def test_render_needs_something_to_draw_and_a_trace(tmp_path, capsys):
    assert main(["render", str(tmp_path / "none.npz"), "--png", "x.png"]) == 2
    assert "no such trace file" in capsys.readouterr().err
    not_a_trace = tmp_path / "bad.npz"
    not_a_trace.write_bytes(b"hello")
    assert main(["render", str(not_a_trace), "--png", str(tmp_path / "x.png")]) == 2
    assert "cannot read it as a trace" in capsys.readouterr().err
    assert main(["render", str(not_a_trace)]) == 2
    assert "nothing to draw" in capsys.readouterr().err


@pytest.mark.parametrize("text", ["1280", "641x360", "10x10", "axb"])
def test_frame_sizes_are_checked(text):
    with pytest.raises(Exception, match="frame|even|size"):
        frame_size(text)
    assert frame_size("1920x1080") == (1920, 1080)


def test_progress_bar_only_on_a_terminal():
    class Terminal(io.StringIO):
        def isatty(self):
            return True

    quiet, loud = io.StringIO(), Terminal()
    for stream in (quiet, loud):
        bar = Progress(10, "writing run.mp4", stream)
        bar.update(5)
        bar.close()
    assert quiet.getvalue() == ""
    assert "writing run.mp4 [" in loud.getvalue() and "10/10 frames" in loud.getvalue()
