"""What the simulation records about each robot for drawing it survives a trace's save and load."""

from ev3sim2d.render.robot_layer import robot_looks
from ev3sim2d.results.trace import Trace


def test_sensor_mounts_and_colour_are_in_the_trace(driving_trace, tmp_path):
    robot = driving_trace.robots[0]
    assert robot["color"] == [230, 170, 30]
    mounts = {m["port"]: m for m in robot["sensor_mounts"]}
    assert mounts["in4"]["kind"] == "ultrasonic" and mounts["in4"]["cone_deg"] == 15
    assert mounts["in3"]["spot_cm"] == 1.5 and mounts["in3"]["facing"] == "down"
    driving_trace.save(tmp_path / "t.npz")
    loaded = Trace.load(tmp_path / "t.npz")
    assert robot_looks(loaded.robots) == robot_looks(driving_trace.robots)


def test_robots_sharing_a_colour_are_drawn_in_different_ones():
    robot = {"name": "r", "color": [230, 170, 30], "sensors": [], "body": None}
    first, second = robot_looks([robot, dict(robot)])
    assert first.color != second.color
