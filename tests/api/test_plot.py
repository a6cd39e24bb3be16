"""Timelines as a chart (ev3sim2d/render/plot.py): the values asked for, against time, as PNG."""

import pytest

from ev3sim2d import simulate

pytest.importorskip("matplotlib")


def test_a_chart_of_the_light_and_the_motor_speeds(tmp_path):
    result = simulate("examples/line_follower.py", world="line", time_s=2)
    figure = result.plot(["in3", "outB.speed", "outC.speed"], path=tmp_path / "chart.png")
    assert len(figure.axes) == 2  # the light, and both speeds in one panel of deg/s
    assert (tmp_path / "chart.png").read_bytes().startswith(b"\x89PNG")


def test_an_unknown_value_lists_the_known_ones():
    result = simulate("print(1)", world="empty", time_s=1)
    with pytest.raises(KeyError, match="no timeline 'in9'.*in3.*outB.speed"):
        result.plot(["in9"])
