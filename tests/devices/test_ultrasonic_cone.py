"""The ultrasonic sensor reads the nearest wall or robot anywhere inside its cone, on every tick.

References:
- ev3dev kernel drivers, github.com/ev3dev/lego-linux-drivers (commit 1b387f3),
  sensors/ev3_uart_sensor_defs.c, LEGO_EV3_ULTRASONIC mode US-DIST-CM: "Continuous measurement",
  value0 the distance in tenths of cm (0-2550).
- python-ev3dev2 2.1.0, ev3dev2/sensor/lego.py: UltrasonicSensor.distance_centimeters (mode
  US-DIST-CM, value0 scaled by 0.1).
- An echo sensor times the first echo that comes back: the nearest object in its beam, whichever
  part of the beam it is in.  ev3sim2d models the beam as a cone `cone_deg` wide (15 by default).
"""

import math
import random
import textwrap

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.maze_file import load_maze, parse_maze, shipped_mazes_dir
from ev3sim2d.world.robot_spec import default_robot

CELL_CM = 4.0
PILLAR = (88.0, 40.0, 92.0, 44.0)  # x0, y0, x1, y1: one wall cell in the middle of the floor
SONAR_CM = 8.0  # the default robot's ultrasonic sensor: 8 cm ahead of the centre, facing ahead


def pillar_world(start: str):
    """A 160 x 100 cm room of 4 cm cells with one wall cell, PILLAR, in it."""
    cols, rows = 40, 25
    walls = {(int(PILLAR[0] // CELL_CM), int(PILLAR[1] // CELL_CM))}
    lines = []
    for row in reversed(range(rows)):
        border = row in (0, rows - 1)
        lines.append(
            "".join(
                "#" if border or col in (0, cols - 1) or (col, row) in walls else "." for col in range(cols)
            )
        )
    grid = textwrap.indent("\n".join(lines), "  ")
    return parse_maze(
        f"title: pillar\ncell_cm: {CELL_CM:g}\ngrid: |\n{grid}\nstart:\n  {start}\n", "<pillar>"
    )


def nearest_on_pillar(x: float, y: float) -> tuple[float, float]:
    """The distance from (x, y) to the pillar, and the direction (radians) of its nearest point."""
    px = min(max(x, PILLAR[0]), PILLAR[2])
    py = min(max(y, PILLAR[1]), PILLAR[3])
    return math.hypot(px - x, py - y), math.atan2(py - y, px - x)


def test_a_pillar_between_the_cones_axis_and_its_edge_is_seen(run):
    """The pillar's near corner is 60.03 cm from the sensor, 1.9 degrees off the axis, and the whole
    pillar lies between the axis and the cone's left edge (7.5 degrees): an echo sensor hears it.  Today
    three rays (axis and edges) pass it on both sides and the reading is the far wall, 128 cm away."""
    result = run(
        """
        import time
        from ev3dev2.sensor.lego import UltrasonicSensor

        sonar = UltrasonicSensor()
        for _ in range(5):
            print(sonar.distance_centimeters)
            time.sleep(0.1)
        """,
        pillar_world("{x_cm: 20, y_cm: 38, heading_deg: 0}"),
    )
    assert result.status == "finished", result.reason
    assert [line.text for line in result.trace.output] == ["60.0"] * 5


def test_the_reading_holds_on_every_tick_as_the_robot_turns(run):
    """While the robot turns slowly on the spot, the pillar stays inside the cone, and every tick's
    measurement (the brick's sample the program reads) is the distance to the pillar's nearest point
    from where the sensor is that tick.  Today the reading jumps between the far wall (while all three
    rays miss the pillar) and the points where one ray crosses it."""
    result = run(
        """
        import time
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
        from ev3dev2.sensor.lego import UltrasonicSensor

        sonar = UltrasonicSensor()
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(SpeedPercent(2), SpeedPercent(-2))  # turning right, about 10 degrees a second
        end = time.time() + 0.6
        while time.time() < end:
            sonar.distance_centimeters
        tank.off()
        """,
        pillar_world("{x_cm: 20, y_cm: 38, heading_deg: 2}"),
    )
    assert result.status == "finished", result.reason
    trace = result.trace
    poses = trace.poses(0)
    half = math.radians(7.5)
    checked = set()
    for t, _robot, port, mode, values in trace.sensor_samples:
        if port != "in4" or mode != "US-DIST-CM":
            continue
        tick = round(t / trace.tick_s)
        x, y, heading = poses[tick]
        h = math.radians(heading)
        sx, sy = x + SONAR_CM * math.cos(h), y + SONAR_CM * math.sin(h)
        distance, direction = nearest_on_pillar(sx, sy)
        off_axis = abs((direction - h + math.pi) % (2 * math.pi) - math.pi)
        assert off_axis < half - math.radians(0.5), (t, heading)  # (the pillar is in the cone throughout)
        assert abs(values[0] / 10 - distance) <= 0.051, (t, heading, values, distance)
        checked.add(tick)
    assert len(checked) >= 58  # every tick of the 0.6 s


def robot_corner_world():
    """Two robots in an arena: the first faces +x; the second stands 40 cm ahead of the first's
    sensor, turned so that one corner of its body points back at that sensor from 3.75 degrees left of
    the sensor's axis, its two faces there sloping away at 45 degrees."""
    sensor = (48.0, 60.0)
    corner_local = (9.0, 7.5)  # the default robot's front-left corner (body and bumper)
    toward = math.radians(3.75)
    corner = (sensor[0] + 40.0 * math.cos(toward), sensor[1] + 40.0 * math.sin(toward))
    heading = math.radians(180 + 3.75 - 45)  # its corner's outward diagonal (45 degrees) at the sensor
    cx = corner[0] - (corner_local[0] * math.cos(heading) - corner_local[1] * math.sin(heading))
    cy = corner[1] - (corner_local[0] * math.sin(heading) + corner_local[1] * math.cos(heading))
    from tests.inline_world import arena

    start = (
        f"- {{x_cm: {sensor[0] - SONAR_CM}, y_cm: {sensor[1]}, heading_deg: 0}}\n"
        f"  - {{x_cm: {cx:.6f}, y_cm: {cy:.6f}, heading_deg: {math.degrees(heading):.6f}}}"
    )
    return arena(start=start)


def test_another_robots_corner_in_the_cone_is_measured_to_the_corner(tmp_path):
    """Another robot's body is a box; its corner 40 cm away, 3.75 degrees off the axis, is the nearest
    thing in the beam, so the first echo comes from it: 39.9 cm (the body's outline is rounded by
    1 mm).  Today the rays on either side of the corner meet its sloping faces 2.6 cm further on."""
    observer = tmp_path / "observer.py"
    observer.write_text(
        "from ev3dev2.sensor.lego import UltrasonicSensor\n"
        "print(round(UltrasonicSensor().distance_centimeters, 1))\n",
        encoding="utf-8",
    )
    standing = tmp_path / "standing.py"
    standing.write_text("import time\ntime.sleep(0.5)\n", encoding="utf-8")
    result = run_programs([observer, standing], robot_corner_world(), time_limit_s=10, hang_after_s=2.0)
    assert result.status == "finished", result.reason
    assert [line.text for line in result.trace.output] == ["39.9"]


@pytest.mark.parametrize("maze", ["maze", "maze-race", "sumo-4"])
def test_the_cone_finds_what_a_fan_of_a_thousand_rays_finds(maze):
    """The cone query (simulator/physics.py, Physics.cone) against brute force: at 300 random poses in a
    shipped world with its robots, for the ultrasonic sensor's 15 degree cone and the infrared sensor's
    30, the distance it gives is never more than the nearest hit of 1001 rays fanned across the cone,
    and at most 0.02 cm less (what the fan misses between its rays); asked twice, it answers the same.
    Today there is no cone query: the three rays miss what lies between them."""
    world = load_maze(shipped_mazes_dir() / f"{maze}.yaml")
    sim = Simulation(world, [(f"r{i}", default_robot(), pose) for i, pose in enumerate(world.starts)])
    physics, group = sim.physics, sim.robots[0].group
    cone = getattr(physics, "cone", None)
    assert cone is not None, "Physics has no cone query"
    rng = random.Random(7)
    floor = [(c, r) for c, r, cell in world.grid.cells() if not cell.wall]
    for _ in range(300):
        col, row = rng.choice(floor)
        x, y = world.grid.cell_center(col, row)
        x, y, direction = x + rng.uniform(-3, 3), y + rng.uniform(-3, 3), rng.uniform(-math.pi, math.pi)
        for cone_deg in (15.0, 30.0):
            half = math.radians(cone_deg) / 2
            fan = 255.0
            for i in range(1001):
                hit = physics.ray(x, y, direction - half + 2 * half * i / 1000, fan, group)
                fan = fan if hit is None else min(fan, hit)
            got = cone(x, y, direction, half, 255.0, group)
            got = 255.0 if got is None else got
            assert fan - 0.02 <= got <= fan + 1e-9, (x, y, direction, cone_deg, got, fan)
            again = cone(x, y, direction, half, 255.0, group)
            assert (255.0 if again is None else again) == got
