"""`ev3sim2d live`: watch programs drive, pause, step, reload, drag robots and edit the world (docs/live.md)."""
