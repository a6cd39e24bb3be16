"""`ev3sim2d show` draws a world file: compared with a stored picture, with a tolerance (fonts and
anti-aliasing may differ by a shade between library versions, the drawing must not)."""

import os
from pathlib import Path

import cv2
import numpy as np

from ev3sim2d.cli import main

GOLDEN = Path(__file__).parent / "golden" / "show_small_maze.png"
SMALL_MAZE = """\
title: Small test maze
cell_cm: 20
legend:
  G: {color: green, region: goal}
grid: |
  ########
  #....GG#
  #.##.GG#
  #.#....#
  #...3r.#
  ########
start:
  cell: [1, 1]
  heading_deg: 90
regions:
  corner:
    cells: [[6, 1]]
"""


def test_show_draws_the_small_maze_like_the_golden_picture(tmp_path):
    maze = tmp_path / "small.yaml"
    maze.write_text(SMALL_MAZE)
    out = tmp_path / "small.png"
    assert main(["show", str(maze), "--png", str(out), "--width", "320"]) == 0
    drawn = cv2.imread(str(out))
    if os.environ.get("EV3SIM2D_UPDATE_GOLDEN"):
        GOLDEN.write_bytes(out.read_bytes())
    golden = cv2.imread(str(GOLDEN))
    assert drawn.shape == golden.shape
    difference = np.abs(drawn.astype(int) - golden.astype(int)).max(axis=2)
    assert difference.mean() < 1.0, (
        f"mean difference {difference.mean():.2f} (EV3SIM2D_UPDATE_GOLDEN=1 to accept)"
    )
    assert np.count_nonzero(difference > 48) < 0.005 * difference.size


def test_show_refuses_a_start_inside_a_wall(tmp_path, capsys):
    maze = tmp_path / "blocked.yaml"
    maze.write_text(SMALL_MAZE.replace("cell: [1, 1]", "x_cm: 24\n  y_cm: 30"))
    assert main(["show", str(maze), "--png", str(tmp_path / "x.png")]) == 2
    assert "inside a wall" in capsys.readouterr().err


def test_show_names_the_shipped_worlds_for_an_unknown_one(tmp_path, capsys):
    assert main(["show", "no-such-world", "--png", str(tmp_path / "x.png")]) == 2
    assert "shipped mazes" in capsys.readouterr().err
