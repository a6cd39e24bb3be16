"""A small lesson written into a temporary folder: drive 30 cm ahead into the goal and stop."""

import textwrap
from pathlib import Path

ROOM = """\
# A room with a goal 30 cm ahead of the start.
title: Test room
cell_cm: 10
legend:
  G: {color: green, region: goal}
grid: |
  ##########
  #........#
  #........#
  #...GG...#
  #........#
  #........#
  ##########
start: {x_cm: 25, y_cm: 35, heading_deg: 0}
"""

LESSON = """\
title: Reach the goal
goal: Drive 30 cm ahead into the green goal and stop there.
time_s: {time_s}
{extra}
variants:
  - name: room
    world: room.yaml
  - name: hidden-room
    world: room.yaml
    hidden: true
    seed: 3
checks:
  - {{name: reach, kind: reach_region, region: goal, points: 3}}
  - {{name: stop, kind: stop_in_region, region: goal, points: 1}}
  - {{name: finished, kind: finished, points: 1}}
"""

GOOD = """\
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_rotations(SpeedPercent(40), SpeedPercent(40), 28 / 17.59)
"""

SHORT = """\
from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent
tank = MoveTank(OUTPUT_B, OUTPUT_C)
tank.on_for_rotations(SpeedPercent(40), SpeedPercent(40), 10 / 17.59)
"""


def write_lesson(folder: Path, time_s: float = 5, extra: str = "", lesson_text: str | None = None) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "room.yaml").write_text(ROOM)
    (folder / "lesson.yaml").write_text(lesson_text or LESSON.format(time_s=time_s, extra=extra))
    return folder


def write_program(folder: Path, name: str, source: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(source))
    return path
