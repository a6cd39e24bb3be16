"""Drawing runs and worlds: readers of the trace, never of the live simulation."""
