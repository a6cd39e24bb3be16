"""Where a beam stops and where a robot touches, from the wall rectangles."""

import math

import pytest

from ev3sim2d.render.walls import Walls

WALLS = Walls([(0, 0, 10, 100), (50, 40, 60, 60)])


def test_a_ray_stops_at_the_first_wall_face():
    assert WALLS.ray(20, 50, 0.0, 255) == pytest.approx(30)  # to the block's left face
    assert WALLS.ray(20, 50, math.pi, 255) == pytest.approx(10)  # back to the long wall
    assert WALLS.ray(20, 10, 0.0, 255) == 255  # nothing that way
    assert WALLS.ray(20, 50, math.pi / 2, 25) == 25


def test_the_point_nearest_a_wall():
    distance, point, wall_point = WALLS.nearest([(30, 50), (12, 20)])
    assert distance == pytest.approx(2) and point == (12, 20) and wall_point == (10, 20)
