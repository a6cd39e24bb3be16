"""Physics reads a robot's contacts from Chipmunk's own structs, once a tick (issue 28).

RobotBody.contacts_now walks its body's arbiter list in Chipmunk's structs instead of asking pymunk's
each_arbiter (a Python callback and objects per contact); the push between robots and the walls' hold
depend on the order of that list, so it must give the same normals in the same order, every tick.
Four robots charge each other in the sumo ring, and two drive into the walls of the maze race.
"""

from __future__ import annotations

import pytest

from ev3sim2d.simulator.physics import WALL
from ev3sim2d.simulator.run import new_simulation
from ev3sim2d.world.maze_file import find_maze, load_maze


def _each_arbiter(robot, physics) -> tuple[list, list]:
    """What pymunk's each_arbiter says: the walls' normals, and the robots touched with their normals."""
    walls, robots = [], []

    def collect(arbiter) -> None:
        mine, other = arbiter.shapes
        assert mine is robot.shape
        n = arbiter.normal
        if other.collision_type == WALL:
            walls.append((n.x, n.y))
        else:
            robots.append((physics.robots[other.body], n.x, n.y))

    robot.body.each_arbiter(collect)
    return walls, robots


@pytest.mark.parametrize(
    ("maze", "count", "left", "right"), [("sumo-4", 4, 600, 600), ("maze-race", 2, 500, 300)]
)
def test_contacts_now_are_what_each_arbiter_says_in_its_order(maze, count, left, right):
    sim, _ = new_simulation(load_maze(find_maze(maze)), count, None, 0, None)
    for robot in sim.robots:
        for motor, speed in ((robot.left, left), (robot.right, right)):
            motor.write("speed_sp", str(speed))
            motor.write("command", "run-forever")
    touched = 0
    for tick in range(1, 601):
        sim.tick(tick * sim.tick_us)
        for robot in sim.robots:
            body = robot.body
            assert body.contacts_now() == _each_arbiter(body, sim.physics), f"tick {tick}, {robot.name}"
            assert len(body.arbiters) == body.contacts
            touched += bool(body.contacts)
    assert touched > 100  # (they did touch)


def test_contacts_are_dropped_with_the_walls_they_touched():
    sim, _ = new_simulation(load_maze(find_maze("maze-race")), 1, None, 0, None)
    robot = sim.robots[0]
    for motor in (robot.left, robot.right):
        motor.write("speed_sp", "500")
        motor.write("command", "run-forever")
    tick = 0
    while not robot.body.touching and tick < 3000:  # into the first wall ahead
        tick += 1
        sim.tick(tick * sim.tick_us)
    assert robot.body.touching and robot.body.contacts_now()[0]
    sim.physics.set_walls(sim.world.grid.wall_rectangles())  # (a cell edited in a live run)
    assert robot.body.contacts_now() == ([], []) and not robot.body.arbiters
    sim.tick((tick + 1) * sim.tick_us)
    assert robot.body.contacts_now() == _each_arbiter(robot.body, sim.physics)
