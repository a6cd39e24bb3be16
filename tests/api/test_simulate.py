"""The Python API as a notebook user calls it: a program as source or file, a world by name or built in Python."""

import math

import numpy as np
import pytest

from ev3sim2d import World, simulate
from ev3sim2d.simulator.program import ProgramError
from ev3sim2d.world import WorldFileError

DRIVE_50_CM = """
    import math
    from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
    MoveTank(OUTPUT_B, OUTPUT_C).on_for_degrees(SpeedPercent(40), SpeedPercent(40), 50 / (math.pi * 5.6) * 360)
    print("there")
"""

LINE_ACROSS = """
    #########################
    #.......................#
    #.......................#
    #...........k...........#
    #.......................#
    #.......................#
    #########################
"""


def across_the_line() -> World:
    return World.from_text(LINE_ACROSS, cell_cm=10, starts=[(8, 3, 0)], name="across")


def test_a_robot_told_to_drive_50_cm_is_50_cm_further_on():
    result = simulate(DRIVE_50_CM, world=across_the_line(), time_s=10)
    assert result.status == "finished"
    start, end = result.poses[0], result.poses[-1]
    assert math.isclose(end[0] - start[0], 50, abs_tol=0.5)
    assert abs(end[1] - start[1]) < 0.1
    assert [line.text for line in result.output] == ["there"]
    assert result.output[0].t_s > 0


def test_timelines_have_one_entry_per_time_and_the_colour_sensor_sees_the_line():
    result = simulate(DRIVE_50_CM, world=across_the_line(), time_s=10)
    n = len(result.times)
    assert result.times[0] == 0 and np.all(np.diff(result.times) > 0)
    assert result.poses.shape == (n, 3)
    assert all(len(values) == n for values in [*result.sensors.values(), *result.motors.values()])
    light = result.sensors["in3"]
    x_sensor = result.poses[:, 0] + 7  # the colour sensor sits 7 cm ahead of the wheels' axle
    on_line = (x_sensor > 121) & (x_sensor < 129)
    assert np.nanmax(light) > 60 and np.nanmin(light[on_line]) < 15
    assert result.motors["outB.speed"].max() > 300
    assert len(result.table(every_s=1.0)) == math.floor(result.times[-1]) + 1


def test_a_result_shows_itself_in_a_notebook_with_a_video_and_a_summary():
    result = simulate(DRIVE_50_CM, world=across_the_line(), time_s=10)
    page = result._repr_html_()
    assert "<video" in page and "data:video/mp4;base64," in page
    assert result.fingerprint in page and "finished" in page


def test_pictures_are_png_and_mp4(tmp_path):
    result = simulate("examples/drive_square.py", world="empty", time_s=1)
    assert result.png(tmp_path / "end.png").startswith(b"\x89PNG")
    assert (tmp_path / "end.png").read_bytes().startswith(b"\x89PNG")
    assert b"ftyp" in result.video(tmp_path / "run.mp4", fps=10, size=(320, 180))[:32]


def test_the_same_program_by_file_and_by_source_does_the_same(tmp_path):
    path = tmp_path / "drive.py"
    path.write_text(DRIVE_50_CM.replace("\n    ", "\n"))
    by_file = simulate(path, world=across_the_line(), time_s=10)
    by_source = simulate(DRIVE_50_CM, world=across_the_line(), time_s=10)
    assert by_file.fingerprint == by_source.fingerprint


def test_several_programs_drive_several_robots():
    result = simulate([DRIVE_50_CM, "print('idle')"], world="line-shared", time_s=5)
    assert [robot.name for robot in result.robots] == ["robot1", "robot2"]
    assert np.array_equal(result.poses, result.robots[0].poses)


def test_bad_input_names_the_thing_and_the_fix(tmp_path):
    with pytest.raises(WorldFileError, match="shipped mazes: .*line"):
        simulate("print(1)", world="no-such-world")
    with pytest.raises(ProgramError, match="missing.py: no such program file"):
        simulate(str(tmp_path / "missing.py"))
    with pytest.raises(ProgramError, match=r"(?s)source, line 2: expected .*if x.*\^"):
        simulate("x = 1\nif x\n    pass\n")
    with pytest.raises(ValueError, match="no robot file 'no-robot'; .*shipped robot"):
        simulate("print(1)", robot="no-robot")
