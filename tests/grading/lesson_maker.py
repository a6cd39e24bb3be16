"""A small lesson written into a temporary folder: drive 30 cm ahead into the goal and stop.

Its goal check is `reach` (the others count once it passes); its hidden variant is in hidden/hidden.yaml.
"""

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
checks:
  - {{name: reach, kind: reach_region, region: goal, goal: true, points: 3}}
  - {{name: stop, kind: stop_in_region, region: goal, points: 1}}
  - {{name: finished, kind: finished, points: 1}}
"""

HIDDEN = """\
variants:
  - name: hidden-room
    world: room.yaml
    seed: 3
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


def write_lesson(
    folder: Path,
    time_s: float = 5,
    extra: str = "",
    lesson_text: str | None = None,
    hidden_text: str | None = HIDDEN,
) -> Path:
    """The lesson folder, with hidden/hidden.yaml unless `hidden_text` is None."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "room.yaml").write_text(ROOM)
    (folder / "lesson.yaml").write_text(lesson_text or LESSON.format(time_s=time_s, extra=extra))
    if hidden_text is not None:
        (folder / "hidden").mkdir(exist_ok=True)
        (folder / "hidden" / "hidden.yaml").write_text(hidden_text)
    return folder


def write_program(folder: Path, name: str, source: str) -> Path:
    path = folder / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(textwrap.dedent(source))
    return path
