"""Every shipped world loads, and a short program runs in it twice with the same fingerprint."""

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.maze_file import find_maze, list_shipped_mazes, load_maze

WANDER = """
from ev3dev2.motor import MoveSteering, OUTPUT_B, OUTPUT_C
from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor, TouchSensor, GyroSensor
steer = MoveSteering(OUTPUT_B, OUTPUT_C)
eye, sonar, bumper, gyro = ColorSensor(), UltrasonicSensor(), TouchSensor(), GyroSensor()
while True:
    if sonar.distance_centimeters < 25 or bumper.is_pressed:
        steer.on_for_degrees(100, 30, 180)
    steer.on(eye.reflected_light_intensity / 10 - 4, 40)
    print(eye.color_name, gyro.angle)
"""


@pytest.mark.parametrize("name", [name for name, _ in list_shipped_mazes()])
def test_shipped_maze_runs_deterministically(name, tmp_path):
    program = tmp_path / "wander.py"
    program.write_text(WANDER)
    world = load_maze(find_maze(name))
    first = run_programs([program], world, time_limit_s=6, hang_after_s=5)
    second = run_programs([program], world, time_limit_s=6, hang_after_s=5)
    assert first.status == "time_limit", first.reason
    assert first.trace.fingerprint() == second.trace.fingerprint()
    assert len(first.trace.output) > 10
    path = first.trace.poses(0)
    assert abs(path[-1][0] - path[0][0]) + abs(path[-1][1] - path[0][1]) > 5  # it moved


def test_the_required_worlds_are_shipped():
    names = {name for name, _ in list_shipped_mazes()}
    assert {"empty", "line", "maze", "colors"} <= names


def test_empty_arena_is_at_least_two_metres_inside_with_the_robot_in_the_middle_facing_x():
    world = load_maze(find_maze("empty"))
    grid = world.grid
    inside_w = (grid.width - 2) * grid.cell_cm
    inside_h = (grid.height - 2) * grid.cell_cm
    assert inside_w >= 200 and inside_h >= 200
    w, h = grid.size_cm
    assert abs(world.start.x_cm - w / 2) < grid.cell_cm and abs(world.start.y_cm - h / 2) < grid.cell_cm
    assert world.start.heading_deg == 0
