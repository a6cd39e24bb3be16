# ruff: noqa
"""Rewrite the trace: find the simulation through threading.enumerate() and the threads' frames, and
make the run's record end with the robot 10 cm from the wall.

The main thread of the process waits in `run_programs`, whose locals hold the Simulation.  The
program swaps the Simulation class's `finish` (called when the program has ended, before the
checks read the trace) for one that moves the last recorded pose to where the sensor is 10 cm
from the wall.

Contained: no simulation or trace is reachable from the program's threads: standing still scores
what standing still scores (never `distance`).
"""

import math
import sys
import threading
import time

MARKER = "EV3CHEAT-threads-rewrite-trace"


def moved_to_the_wall(finish):
    def finish_and_move(sim):
        trace = finish(sim)
        from ev3sim2d.grading.world_geometry import distance_to_wall

        sonar = next(s for s in sim.world.robot.sensors if s.kind == "ultrasonic")
        last = len(trace.values) - trace.width
        x, y, heading = trace.values[last], trace.values[last + 1], trace.values[last + 2]
        h = math.radians(heading)
        forward, left = sonar.offset_cm
        sx = x + forward * math.cos(h) - left * math.sin(h)
        sy = y + forward * math.sin(h) + left * math.cos(h)
        shift = distance_to_wall(sim.world.grid, sx, sy, heading + sonar.aim_deg) - 10
        trace.values[last] += shift * math.cos(h)
        trace.values[last + 1] += shift * math.sin(h)
        return trace

    return finish_and_move


frames = sys._current_frames()
for thread in threading.enumerate():
    frame = frames.get(thread.ident)
    while frame is not None:
        sim = frame.f_locals.get("sim")
        if sim is not None and hasattr(type(sim), "finish"):
            type(sim).finish = moved_to_the_wall(type(sim).finish)
            print("found the simulation in", thread.name)
            break
        frame = frame.f_back
time.sleep(0.1)  # a few ticks in the trace, to rewrite the last of
