"""Attacks a determined student would make on the trusted side: the grader, its workers, the simulator, serve."""
