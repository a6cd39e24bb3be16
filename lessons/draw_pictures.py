#!/usr/bin/env python3
"""Draw the picture of each lesson's visible variants for its README: lessons/<id>/<variant>.png.

Run after changing a lesson's worlds:  python lessons/draw_pictures.py [LESSON ...]
Hidden variants get no picture: students do not see them.
"""

import sys
import tempfile
from pathlib import Path

from ev3sim2d.grading.lesson import list_shipped_lessons, load_lesson
from ev3sim2d.render import frame
from ev3sim2d.simulator.run import run_programs


def draw(lesson_id: str) -> list[Path]:
    lesson = load_lesson(lesson_id)
    written = []
    with tempfile.TemporaryDirectory() as folder:
        still = Path(folder) / "still.py"
        still.write_text("pass\n")
        for variant in lesson.visible_variants():
            robots = len(variant.robot_names)  # the student's and the lesson's other robots, where they start
            trace = run_programs([still] * robots, variant.world(), time_limit_s=0.01).trace
            path = lesson.folder / f"{variant.name}.png"
            frame.save_png(frame.draw_world_picture(trace, 640), path)
            written.append(path)
    return written


if __name__ == "__main__":
    for lesson_id in sys.argv[1:] or list_shipped_lessons():
        for path in draw(lesson_id):
            print(path)
