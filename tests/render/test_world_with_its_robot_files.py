"""Pictures and videos of a world whose robot files are named relative to the world file.

A world names its robot (`robot: mybot.yaml`, and a start's `robot:`) as a file next to the world file.
A run from another folder finds it there; its pictures must too, and a trace drawn later, once the
world's folder is gone, is drawn from what the trace holds (its robots' shapes are in it).
"""

import shutil
from pathlib import Path

import cv2

from ev3sim2d import cli
from ev3sim2d.world.robot_spec import shipped_robots_dir

DRIVE = "from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C\nMoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)\n"


def _world_folder(tmp_path: Path) -> Path:
    folder = tmp_path / "worlds"
    (folder / "robots").mkdir(parents=True)
    base = (shipped_robots_dir() / "ev3-driving-base.yaml").read_text()
    (folder / "mybot.yaml").write_text(base.replace("name: ", "name: mybot # ", 1))
    (folder / "robots" / "wide.yaml").write_text(base.replace("name: ", "name: wide # ", 1))
    grid = "\n".join("  " + row for row in ["#" * 12, *["#" + "." * 10 + "#"] * 6, "#" * 12])
    (folder / "world.yaml").write_text(
        "title: two robots of our own\nrobot: mybot.yaml\ncell_cm: 12\ngrid: |\n"
        f"{grid}\n"
        "start:\n"
        "  - {x_cm: 30, y_cm: 30, heading_deg: 0}\n"
        "  - {x_cm: 30, y_cm: 60, heading_deg: 0, robot: robots/wide.yaml}\n"
    )
    return folder


def test_run_from_another_folder_writes_its_picture_and_video(tmp_path, monkeypatch, capsys):
    worlds = _world_folder(tmp_path)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    (elsewhere / "a.py").write_text(DRIVE)
    (elsewhere / "b.py").write_text(DRIVE)
    monkeypatch.chdir(elsewhere)
    status = cli.main(
        ["run", "a.py", "b.py", "--maze", "../worlds/world.yaml", "--time", "2"]
        + ["--png", "end.png", "--video", "run.mp4", "--trace", "run.npz"]
    )
    err = capsys.readouterr().err
    assert status == 0, err
    assert "Traceback" not in err and "WorldFileError" not in err
    picture = cv2.imread(str(elsewhere / "end.png"))
    assert picture is not None and picture.shape[0] > 100
    video = cv2.VideoCapture(str(elsewhere / "run.mp4"))
    assert video.isOpened() and video.get(cv2.CAP_PROP_FRAME_COUNT) > 10

    # the world's folder is gone: the trace is still drawn, with the robots it holds
    shutil.rmtree(worlds)
    other = tmp_path / "later"
    other.mkdir()
    monkeypatch.chdir(other)
    status = cli.main(["render", str(elsewhere / "run.npz"), "--png", "again.png"])
    assert status == 0, capsys.readouterr().err
    again = cv2.imread(str(other / "again.png"))
    assert again is not None and again.shape == picture.shape
    assert abs(again.astype(int) - picture.astype(int)).mean() < 1.0
