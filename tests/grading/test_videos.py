"""`--videos`: what is kept of a failed run, with or without a video writer."""

from ev3sim2d.grading import videos
from ev3sim2d.results.trace import Trace
from ev3sim2d.simulator.run import run_programs

from .trace_maker import room


def a_trace_file(tmp_path):
    prog = tmp_path / "prog.py"
    prog.write_text("import time\ntime.sleep(0.2)\n")
    trace = run_programs([prog], room(), time_limit_s=1).trace
    path = tmp_path / "trace.npz"
    trace.save(path)
    return path


def test_without_a_video_writer_the_trace_and_a_picture_are_kept(tmp_path, monkeypatch):
    monkeypatch.setattr(videos, "video_writer", lambda: None)
    kept = videos.keep_failed_run(tmp_path / "out", "class/alice.py", "room", a_trace_file(tmp_path))
    assert [p.relative_to(tmp_path / "out").as_posix() for p in kept] == ["alice/room.npz", "alice/room.png"]
    assert Trace.load(kept[0]).result["status"] == "finished"
    assert kept[1].read_bytes()[:4] == b"\x89PNG"


def test_with_a_video_writer_a_video_is_written(tmp_path, monkeypatch):
    written = []
    monkeypatch.setattr(videos, "video_writer", lambda: lambda trace, path: written.append((trace, path)))
    kept = videos.keep_failed_run(tmp_path / "out", "class/bob", "maze-b", a_trace_file(tmp_path))
    assert kept == [tmp_path / "out" / "bob" / "maze-b.mp4"]
    assert written and written[0][1] == kept[0]


def test_folder_names_are_safe():
    assert videos.folder_name("class/alice.py") == "alice"
    assert videos.folder_name("/tmp/x/bob/") == "bob"
    assert videos.folder_name("weird name!.py") == "weird_name"
