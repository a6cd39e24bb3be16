# ruff: noqa
"""Move the wall: edit the world in memory so that a wall stands 10 cm ahead of the robot.

The program finds the running Simulation with gc and replaces its world's grid (the one the
`distance` check measures on) by a fine grid with a single wall cell 10 cm straight ahead of the
ultrasonic sensor.  The robot never moves, yet the check finds the wall at 10 cm.

Contained: the world the checks read is not in the program's process: standing still scores
what standing still scores (never `distance`).
"""

import gc
import math

MARKER = "EV3CHEAT-move-the-wall"
CELL_CM = 0.5

try:
    import ev3sim2d.simulator.simulation
    from ev3sim2d.world.grid import Grid

    for sim in [o for o in gc.get_objects() if isinstance(o, ev3sim2d.simulator.simulation.Simulation)]:
        world, robot = sim.world, sim.robots[0]
        sonar = next(s for s in world.robot.sensors if s.kind == "ultrasonic")
        forward, left = sonar.offset_cm
        h = robot.heading_rad
        sx = robot.x + forward * math.cos(h) - left * math.sin(h)
        sy = robot.y + forward * math.sin(h) + left * math.cos(h)
        aim = h + math.radians(sonar.aim_deg)
        px, py = sx + 10.0 * math.cos(aim), sy + 10.0 * math.sin(aim)
        old = world.grid
        wall = next(old.cell(c, r) for c, r in old.wall_cells())
        floor = old.cell(1, 1)
        width, height = int(old.size_cm[0] / CELL_CM), int(old.size_cm[1] / CELL_CM)
        rows = [[floor] * width for _ in range(height)]
        rows[int(py / CELL_CM)][int(px / CELL_CM)] = wall
        world.grid = Grid(rows, CELL_CM)
except Exception as err:
    print("no world to change:", err)
