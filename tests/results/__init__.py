"""Tests of what a run leaves (ev3sim2d/results/)."""
