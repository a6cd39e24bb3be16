"""Simulated EV3 hardware, one file per kind of device (see registry.py)."""
