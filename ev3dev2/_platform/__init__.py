"""Per-platform port names, LEDs and buttons; the simulated brick is always an EV3."""
