# ruff: noqa
"""Litter: leave files in the temporary folders (tempfile's, /tmp, /var/tmp, /dev/shm) that nobody removes.

Contained: the program writes only in its scratch folder, which goes with the run: the grader's
TMPDIR is empty after the run and no file named after the marker is left in /tmp, /var/tmp or
/dev/shm; the program stands still and scores what standing still scores.
"""

import os
import tempfile

MARKER = "EV3CHEAT-litter-temp"

places = [tempfile.mkdtemp(prefix=MARKER + "-")]
for folder in ("/tmp", "/var/tmp", "/dev/shm"):
    places.append(os.path.join(folder, f"{MARKER}-{os.getpid()}"))
for place in places:
    try:
        os.makedirs(place, exist_ok=True)
        with open(os.path.join(place, "junk.bin"), "wb") as f:
            f.write(os.urandom(1 << 16))
    except OSError as err:
        print("cannot litter", place, err)
