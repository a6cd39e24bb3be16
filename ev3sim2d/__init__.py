"""ev3sim2d: a 2D top-down simulator for LEGO Mindstorms EV3 robots."""
