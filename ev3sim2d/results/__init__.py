"""What a run leaves, and its readings: the trace, its series, the JSON summary and small tables.

Written by the simulation while it runs; read afterwards by the renderer, the grader, the live
page and the Python API, never the live simulation.
"""
