"""Lessons and auto-grading: run a student's program in a lesson's worlds and score what happened.

A lesson (`lessons/<id>/lesson.yaml`, read by `lesson.py`) names its variants
(a world, a start, a robot, a seed: `variant.py`) and its checks (`check.py`,
kinds in `checks/`).  `submission.py` finds the programs to grade, `worker.py`
runs each one in each variant in a process of its own with limits and scores
the run (`scoring.py`, the checks reading a `RunRecord` of the trace and world),
`grader.py` runs those processes in parallel and keeps the results as they
come (`result.py`), and `report.py` writes the table, JSON, JUnit and CSV.
Docs: docs/lessons.md.
"""
