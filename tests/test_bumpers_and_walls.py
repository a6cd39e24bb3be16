"""A touch sensor's bumper is a segment, and walls have friction.

A real EV3 touch sensor is a button; robots put a bumper on it (the Robot Educator base's front
bumper spans the robot's front), so a wall anywhere along the bumper pushes the button in.  A
robot that meets a wall at an angle touches it first with a corner of its front, and with a
point-sized bumper in the middle it would stall against the wall unnoticed.  Walls are not ice:
a robot pushed at an angle against a wall slides along it slowed by friction (physics.py,
WALL_FRICTION, the Coulomb model for a body driven at a set speed).
"""

from __future__ import annotations

import math

import pytest

from ev3sim2d.simulator.physics import WALL_FRICTION
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.robot_spec import parse_robot
from tests.inline_world import arena, two_wheel_robot

TICK_S = 0.01


def _sim(x_cm: float, y_cm: float, heading_deg: float, robot=None) -> Simulation:
    world = arena(start=f"x_cm: {x_cm}\n  y_cm: {y_cm}\n  heading_deg: {heading_deg}")
    return Simulation(world, [("robot", robot or world.robot, world.start)])


def _drive(sim: Simulation, left_dps: int, right_dps: int) -> None:
    robot = sim.robots[0]
    for motor, speed in ((robot.left, left_dps), (robot.right, right_dps)):
        motor.write("speed_sp", str(speed))
        motor.write("command", "run-forever")


def _run(sim: Simulation, seconds: float, until=None) -> float | None:
    """Tick for up to `seconds`; the time at which until(robot) first held (None: never)."""
    robot = sim.robots[0]
    for i in range(int(round(seconds / TICK_S))):
        sim.tick((i + 1) * 10_000)
        if until is not None and until(robot):
            return (i + 1) * TICK_S
    return None


def _pressed(robot) -> bool:
    return robot.sensors["in1"].values() == (1,)


# the arena's inside is x, y in [12, 228] cm; the robot's front is 9 cm ahead of its centre


@pytest.mark.parametrize("angle_deg", [0, 20, 40, 60])
def test_a_robot_that_meets_a_wall_at_an_angle_presses_its_front_bumper(angle_deg):
    sim = _sim(190, 120, angle_deg)  # toward the right-hand wall, angle_deg off straight at it
    _drive(sim, 300, 300)
    pressed_at = _run(sim, 6.0, _pressed)
    assert pressed_at is not None, "the bumper was never pressed"
    robot = sim.robots[0]
    front_corners_x = [
        robot.x + 9 * math.cos(robot.heading_rad) + s * 7.5 * math.sin(robot.heading_rad) for s in (-1, 1)
    ]
    assert max(front_corners_x) > 226.5  # pressed when the front (a corner of it) reached the wall


def test_a_robot_cannot_wedge_itself_into_a_corner_unnoticed():
    sim = _sim(190, 190, 45)  # straight into the top right corner, diagonally
    _drive(sim, 300, 300)
    _run(sim, 6.0)
    robot = sim.robots[0]
    assert robot.body.touching  # it is stuck in the corner ...
    assert _pressed(robot)  # ... and its bumper says so
    assert "stalled" in robot.left.read("state").split()  # so do its motors


def test_a_wall_along_the_robots_side_does_not_press_the_front_bumper():
    """Sliding along a wall with the side does not push a front bumper in."""
    sim = _sim(120, 12 + 7.5 + 0.2, 0)  # along the bottom wall, its right side 2 mm from it
    _drive(sim, 300, 290)  # a slight turn to the right: the side presses on the wall
    touched = _run(sim, 3.0, lambda r: r.body.touching)
    assert touched is not None  # the side does touch the wall ...
    assert _run(sim, 1.0, _pressed) is None  # ... and sliding along it never presses the bumper


def test_a_bare_button_presses_only_at_its_tip():
    """bumper_cm: 2 (the default) is the sensor's own button: a wall meeting the robot's corner first
    does not reach it."""
    spec = parse_robot(
        two_wheel_robot(
            "narrow bumper", "{port: 1, kind: touch, angle_deg: 0, radius_cm: 9, facing: forward}"
        ),
        "<narrow bumper>",
    )
    sim = _sim(190, 120, 60, robot=spec)
    _drive(sim, 300, 300)
    touched = _run(sim, 6.0, lambda r: r.body.touching)
    assert touched is not None  # its corner meets the wall (at about 3.7 s) ...
    assert _run(sim, 1.0, _pressed) is None  # ... and slides along it, the button well clear


def test_friction_slows_a_robot_sliding_along_a_wall():
    """Pushed at 45 degrees against a wall, a robot slides along it at (1 - WALL_FRICTION) of the
    speed it would have on a frictionless wall: its push into the wall equals its sliding speed."""
    sim = _sim(205, 120, 45)  # toward the right-hand wall at 45 degrees
    _drive(sim, 360, 360)  # 360 deg/s: 17.6 cm/s with 56 mm wheels
    assert _run(sim, 3.0, lambda r: r.body.touching) is not None
    _run(sim, 0.3)  # settled against the wall
    robot = sim.robots[0]
    y0 = robot.y
    _run(sim, 2.0)
    speed = math.pi * 5.6 * 360 / 360  # cm/s
    sliding = (robot.y - y0) / 2.0
    frictionless = speed * math.sin(math.radians(45))
    assert robot.body.touching
    assert sliding == pytest.approx(frictionless * (1 - WALL_FRICTION), rel=0.1)
    assert sliding < 0.75 * frictionless
