#!/usr/bin/env python3
"""Sound: a beep, a tone sequence, a note and speech (the video shows and plays them).

Try it:  ev3sim2d run examples/sound.py
"""

import time

from ev3dev2.sound import Sound

speaker = Sound()
speaker.set_volume(80)
speaker.beep()
speaker.tone([(392, 350, 100), (492, 350, 100), (587, 350, 100)])
speaker.play_note("A4", 0.5)
speaker.speak("Hello from the simulator")
print("done at", round(time.monotonic() % 1000, 2), "s")
