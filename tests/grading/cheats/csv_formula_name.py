# ruff: noqa
"""A name that is a formula: handed in as `=HYPERLINK("evil.example","40 of 40").py`, so that when the teacher
runs `ev3sim2d grade LESSON .` in the class folder the CSV's first cell of this row is a spreadsheet formula.

The program itself stands still.

Contained: no cell of the CSV starts with `=`, `+`, `-` or `@` (or it is quoted so that a
spreadsheet reads it as text, e.g. with a leading `'`); the program scores what standing still scores.
"""

MARKER = "EV3CHEAT-csv-formula-name"
print("a program with a name")
