"""`ev3sim2d plot TRACE` and `run --plot`: a run's values against time as a PNG chart, as a user runs them."""

import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

pytest.importorskip("matplotlib")

REPO = Path(__file__).resolve().parents[2]
LINE_FOLLOWER = REPO / "examples" / "line_follower.py"


def ev3sim2d(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "ev3sim2d", *map(str, args)],
        cwd=cwd,
        capture_output=True,
        text=True,
        timeout=120,
    )


@pytest.fixture(scope="module")
def trace(tmp_path_factory):
    """A line follower's 8 s on the line world (it reaches the line after 6 s), saved as a trace."""
    folder = tmp_path_factory.mktemp("plot")
    done = ev3sim2d(
        "run", LINE_FOLLOWER, "--maze", "line", "--time", 8, "--quiet", "--trace", "run.npz", cwd=folder
    )
    assert done.returncode == 0, done.stderr
    return folder / "run.npz"


def test_a_chart_of_the_asked_size_that_shows_the_asked_values(trace, tmp_path):
    light = ev3sim2d(
        "plot", trace, "--png", "light.png", "--values", "in3", "--size", "640x480", cwd=tmp_path
    )
    assert light.returncode == 0, light.stderr
    speeds = ev3sim2d(
        "plot", trace, "--png", "speeds.png", "--values", "outB.speed", "--values", "outC.speed",
        "--size", "640x480", cwd=tmp_path,
    )  # fmt: skip
    assert speeds.returncode == 0, speeds.stderr
    light_px, speeds_px = cv2.imread(str(tmp_path / "light.png")), cv2.imread(str(tmp_path / "speeds.png"))
    assert light_px.shape == speeds_px.shape == (480, 640, 3)
    assert light_px.std() > 10  # not blank: axes, labels, a curve
    assert np.mean(light_px != speeds_px) > 0.01


def test_without_values_it_draws_what_changed(trace, tmp_path):
    done = ev3sim2d("plot", trace, "--png", "plot.png", "--from", 5, "--to", 8, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    picture = cv2.imread(str(tmp_path / "plot.png"))
    assert picture.shape[1] == 800 and picture.shape[0] > 500  # a panel each: gyro, light, distance, speeds


def test_list_names_the_values_with_their_units(trace, tmp_path):
    done = ev3sim2d("plot", trace, "--list", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    lines = dict(line.split(maxsplit=1) for line in done.stdout.splitlines())
    assert lines["in3"] == "color sensor: reflected light (%)"
    assert lines["in4"] == "ultrasonic sensor: distance (cm)"
    assert lines["outB.speed"] == "large motor outB: speed (°/s)"
    assert lines["outB.position"] == "large motor outB: position (°)"
    assert {"x_cm", "y_cm", "heading_deg", "touching"} <= set(lines)


def test_the_distance_is_in_centimetres_as_the_program_reads_it(trace):
    from ev3sim2d.render.plot import timelines
    from ev3sim2d.results.series import robot_series
    from ev3sim2d.results.trace import Trace

    loaded = Trace.load(trace)
    raw = robot_series(loaded, 0).sensors["in4"]  # the driver's value0: tenths of a cm
    assert np.allclose(timelines(loaded, 0)["in4"].values, raw / 10, equal_nan=True)


def test_run_plot_writes_the_chart_at_the_end(tmp_path):
    done = ev3sim2d(
        "run", LINE_FOLLOWER, "--maze", "line", "--time", 2, "--quiet",
        "--plot", "plot.png", "--plot-values", "in3,outB.speed", cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "plot.png").read_bytes().startswith(b"\x89PNG")


def test_run_plot_with_an_unknown_value_says_which_and_the_known_ones(tmp_path):
    done = ev3sim2d(
        "run", LINE_FOLLOWER, "--maze", "line", "--time", 1, "--quiet",
        "--plot", "plot.png", "--plot-values", "in9", cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 2
    assert "--plot-values: no timeline 'in9'" in done.stderr and "outB.speed" in done.stderr


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--png", "p.png", "--values", "in9"], "--values: no timeline 'in9' for robot; there are: "),
        (
            ["--png", "missing/p.png"],
            "missing/p.png: cannot write the plot (No such file or directory); give a path",
        ),
        (["--png", "p.png", "--robot", "2"], "--robot 2: the trace has 1 robot(s); give 1 to 1"),
        (["--png", "p.png", "--from", "5", "--to", "2"], "--from must come before --to"),
        ([], "nothing to do: give --png FILE"),
    ],
)
def test_mistakes_are_told_in_one_line(trace, tmp_path, args, message):
    done = ev3sim2d("plot", trace, *args, cwd=tmp_path)
    assert done.returncode == 2
    assert done.stderr.startswith("ev3sim2d: error: ") and message in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1


def test_a_file_that_is_not_a_trace(tmp_path):
    (tmp_path / "notes.npz").write_text("hello")
    np.savez(tmp_path / "numbers.npz", a=[1, 2])
    for name in ("notes.npz", "numbers.npz", "none.npz"):
        done = ev3sim2d("plot", name, "--png", "p.png", cwd=tmp_path)
        assert done.returncode == 2
        assert done.stderr.startswith(f"ev3sim2d: error: {name}: ")
        assert "`ev3sim2d run PROG --trace FILE`" in done.stderr


def test_without_matplotlib_it_says_how_to_install_it(trace, tmp_path):
    hide = "import sys; sys.modules['matplotlib'] = None; from ev3sim2d.cli import main; sys.exit(main(sys.argv[1:]))"
    for args in (["plot", trace, "--png", "p.png"], ["run", LINE_FOLLOWER, "--plot", "p.png"]):
        done = subprocess.run(
            [sys.executable, "-c", hide, *map(str, args)], cwd=tmp_path, capture_output=True, text=True
        )
        assert done.returncode == 2
        assert "pip install 'ev3sim2d[plot]'" in done.stderr
    listed = subprocess.run(
        [sys.executable, "-c", hide, "plot", str(trace), "--list"],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert listed.returncode == 0 and "in3" in listed.stdout  # --list needs no matplotlib
