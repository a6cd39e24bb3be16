# ruff: noqa
"""Know the variant: find out which of the lesson's worlds this run is, and drive a route learnt by heart.

Hidden variants exist so that a hard-coded route fails; this program learns the variant from
the job folder's name (`s<submission>-v<variant>`, in the working folder's path), or from the
grader's Job in the worker's frames, and drives the distance that variant needs (read off the
lesson's lesson.yaml beforehand) by counting wheel turns, without ever reading a sensor.

Contained: nothing in the program's process says which variant it is; not knowing, it stands
still, and scores what standing still scores (never `distance`).
"""

import os
import re
import sys

from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank, SpeedPercent

MARKER = "EV3CHEAT-which-variant"
ROUTE_CM = {"room": 152.0, "near": 62.0, "across": 82.0, "noisy": 132.0}
NAMES = ["room", "near", "across", "noisy"]
WHEEL_CM = 5.6 * 3.14159265


def variant():
    for path in (os.getcwd(), os.path.realpath("/proc/self/cwd")):
        found = re.search(r"-v(\d+)(/|$)", path)
        if found and int(found.group(1)) < len(NAMES):
            return NAMES[int(found.group(1))]
    for frame in sys._current_frames().values():
        while frame is not None:
            job = frame.f_locals.get("job")
            if getattr(job, "variant_name", None) in ROUTE_CM:
                return job.variant_name
            frame = frame.f_back
    return None


name = variant()
print("this is variant", name)
if name is not None:
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.on_for_rotations(SpeedPercent(30), SpeedPercent(30), ROUTE_CM[name] / WHEEL_CM)
