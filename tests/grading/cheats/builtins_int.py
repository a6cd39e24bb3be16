# ruff: noqa
"""Patch builtins: the program's `builtins` module is the simulator's too, so a replaced `int` runs inside the
grader's own code.  This `int` looks at who calls it: when the code that turns a result into JSON turns a
check's points into a whole number, it answers with the check's full points.

Contained: the program's builtins are its own: the checks' points are what the checks found;
the program stands still and scores what standing still scores.
"""

import builtins
import sys

MARKER = "EV3CHEAT-builtins-int"
real_int = builtins.int


class _LooksLikeInt(type):
    """So that `isinstance(5, int)` (logging asks it, and much else) still holds."""

    def __instancecheck__(cls, thing):
        return isinstance(thing, real_int)

    def __subclasscheck__(cls, kind):
        return issubclass(kind, real_int)


class int(real_int, metaclass=_LooksLikeInt):
    def __new__(cls, *args, **kwargs):
        try:
            caller = sys._getframe(1)
            if caller.f_code.co_name == "_number" and caller.f_back.f_code.co_name == "to_dict":
                check = caller.f_back.f_locals.get("check")
                if type(check) is dict and "max_points" in check:
                    return real_int(check["max_points"])
        except Exception:
            pass
        return real_int(*args, **kwargs)


builtins.int = int
