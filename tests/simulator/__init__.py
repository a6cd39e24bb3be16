"""Tests of the simulator process (ev3sim2d/simulator/)."""
