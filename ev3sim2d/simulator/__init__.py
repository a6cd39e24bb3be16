"""The simulator process: the world in motion, and the bricks that drive it, in lockstep.

A run flows through it like this: `run.py` loads each program (`program.py`), builds the
world's physics (`physics.py`) and robots (`robot.py`) in a `Simulation` (`simulation.py`),
starts a brick per program (`bricks.py`, or forked from a class run's zygote: `zygote.py`),
and hands each brick's connection to a `BrickPort` (`brick_port.py`), which checks and
applies what the brick sends to its robot's devices.  The `Session` (`session.py`) steps the
world tick by tick once every brick has passed the tick, until the programs end, the time
limit, or a hang; the run's result holds the trace (`ev3sim2d/results/`).  `lobby.py` seats
bricks that join over TCP from other computers (`ev3sim2d serve`).

Nothing here imports the brick's own code (`ev3sim2d/brick/`): the two sides meet only
through `ev3sim2d/protocol/`.
"""
