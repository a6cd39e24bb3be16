# ruff: noqa
"""A symlink for a program: a student's folder whose `main.py` is a symbolic link (git keeps them) to a file
of the teacher's, here `~/.git-credentials` (`https://user:TOKEN@github.com`).  The grader reads the
program with the teacher's rights and reports its syntax error with the offending line, which is the
file's first line: the token is in the JSON, the CSV and the JUnit XML.  The test hands this in as
`symlink_main/main.py` -> `$HOME/.git-credentials` (this file beside it, as `notes.py`).

Contained: a program is read only inside the submission (a link out of it is refused, or read with the
program's rights): nothing of the linked file appears in the reports; the submission scores nothing
or what standing still scores.
"""

MARKER = "EV3CHEAT-symlink-main"
