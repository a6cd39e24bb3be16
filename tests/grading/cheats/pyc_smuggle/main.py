# ruff: noqa
"""Smuggle a .pyc: a student's folder whose `helper.py` is harmless, handed in with a `__pycache__/helper.cpython-3XX.pyc`
compiled from other code (`_compiled_helper.py`, which the student leaves out) as an *unchecked* hash-based
pyc (PEP 552): Python loads it without looking at helper.py, and the grader's key of the submission
leaves `__pycache__` out.  A teacher who reads main.py and helper.py sees nothing wrong.

The compiled helper gives every check full marks (it swaps ev3sim2d's score_run for one that passes
everything, as patch_score_run.py does).

Contained: the program runs helper.py as written (no pyc that came with the submission is loaded, or
the one that is can reach no scorer): it stands still and scores what standing still scores.
"""

import helper

MARKER = "EV3CHEAT-pyc-smuggle"
helper.say_hello()
