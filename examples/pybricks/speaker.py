#!/usr/bin/env pybricks-micropython
"""The brick's speaker: a beep, a tune, a sound file and speech; each waits until it has been played.

Try it:  ev3sim2d run examples/pybricks/speaker.py --maze empty
"""

from pybricks.hubs import EV3Brick
from pybricks.media.ev3dev import SoundFile

ev3 = EV3Brick()

ev3.speaker.set_volume(50)  # percent
ev3.speaker.beep()  # 500 Hz for 100 ms
ev3.speaker.beep(frequency=880, duration=300)
ev3.speaker.play_notes(["C4/4", "E4/4", "G4/2"], tempo=120)
ev3.speaker.play_file(SoundFile.HELLO)
ev3.speaker.say("Hello from the simulator")
print("all played")
