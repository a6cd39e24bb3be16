#!/usr/bin/env pybricks-micropython
"""The brick's screen: text, shapes and print(), as the EV3's 178 x 128 pixel LCD shows them.

Try it:  ev3sim2d run examples/pybricks/screen.py --maze empty --lcd lcd.png
"""

from pybricks.hubs import EV3Brick
from pybricks.parameters import Color
from pybricks.tools import wait

ev3 = EV3Brick()
screen = ev3.screen

screen.clear()
screen.draw_text(10, 10, "Hello, EV3!")
wait(500)

screen.draw_box(10, 40, 80, 100, r=5)  # an outline with round corners
screen.draw_circle(130, 70, 25, fill=True)  # a black disc
screen.draw_line(0, 127, 177, 0, width=2)
wait(500)

screen.clear()
screen.print("line one")  # print() writes line after line, as on a console
screen.print("line", 2, sep=" ")
screen.draw_text(10, 100, "white on black", text_color=Color.WHITE, background_color=Color.BLACK)
print("screen is", screen.width, "x", screen.height)
