"""Named regions: which points they hold and where their middle is."""

import pytest

from ev3sim2d.world.pose import Pose
from ev3sim2d.world.region import Region


def test_a_region_holds_points_inside_its_rectangles_left_and_bottom_edges_included():
    goal = Region("goal", ((0.0, 0.0, 10.0, 10.0), (10.0, 0.0, 20.0, 5.0)))
    assert goal.contains(0, 0)
    assert goal.contains(15, 4.9)
    assert not goal.contains(15, 5)
    assert not goal.contains(20, 1)
    assert not goal.contains(-0.1, 5)


def test_centre_is_area_weighted_and_bounds_enclose_everything():
    region = Region("l", ((0.0, 0.0, 10.0, 10.0), (10.0, 0.0, 30.0, 10.0)))
    assert region.center() == pytest.approx((15.0, 5.0))
    assert region.bounds() == (0.0, 0.0, 30.0, 10.0)
    assert region.area_cm2() == 300


def test_plain_values_for_traces():
    assert Region("a", ((1.0, 2.0, 3.0, 4.0),)).as_dict() == {"name": "a", "rects": [[1.0, 2.0, 3.0, 4.0]]}
    assert Pose(1.0, 2.0, 90.0).as_dict() == {"x_cm": 1.0, "y_cm": 2.0, "heading_deg": 90.0}
