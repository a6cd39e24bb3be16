"""How the firmware reads a number argument: pb_obj_get_int (pybricks-micropython v2.0.0, py/pbobj.c).

A float is truncated toward zero (`wait(0.5)` waits 0 ms, `run_angle(500.9, 90.9)` turns 90 degrees),
an int or a bool is taken as it is, and anything else is a TypeError, as MicroPython's
mp_obj_get_int says it.
"""


def get_int(value) -> int:
    """The argument as the firmware's C code gets it."""
    if isinstance(value, float):
        return int(value)
    if isinstance(value, int):
        return int(value)  # (a bool is 0 or 1)
    if hasattr(value, "__index__"):
        return value.__index__()
    raise TypeError(f"can't convert {type(value).__name__} to int")
