"""Tests of what runs in the brick process (ev3sim2d/brick/)."""
