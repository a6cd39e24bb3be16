"""Python's "Did you mean" for a misspelt name, on every Python a brick may run on.

A student who writes `LargeMotr`, `from ev3dev2.motor import LargeMotr` or `motor.on_for_rotation(...)`
gets from Python 3.12 and later, at a terminal, the line `NameError: name 'LargeMotr' is not defined.
Did you mean: 'LargeMotor'?`.  Python 3.10 and 3.11 print the hint for a NameError and an
AttributeError at the terminal only (the interpreter's own display, not the traceback module), and
none for an ImportError; and the traceback module of 3.12 leaves out a NameError's.  The brick
formats the program's error itself, so it adds the hint itself, the same on every Python: for a
name not found (among the failing frame's locals, globals and builtins), an attribute not found
(among the object's), and a name a `from ... import` did not find (among the module's).

How a name is chosen follows CPython's Lib/traceback.py (`_compute_suggestion_error`): a
Levenshtein distance in which changing a letter's case costs 1 and any other edit 2, the
nearest name within (len(a) + len(b) + 3) * 2 // 6 of the wrong one, at most 750 candidates
and 40 characters.
"""

from __future__ import annotations

import re
import sys

MAX_CANDIDATES = 750
MAX_NAME = 40
MOVE_COST = 2
CASE_COST = 1
_CANNOT_IMPORT = re.compile(r"^cannot import name '([^']+)' from '([^']+)'")


def suggestion(exc: BaseException) -> str | None:
    """The name Python would suggest for exc, or None."""
    try:
        wrong, candidates = _wrong_name_and_candidates(exc)
    except Exception:  # noqa: BLE001 - a program's object whose dir() fails: no hint, as Python gives none
        return None
    if isinstance(exc, NameError) and wrong and candidates is None:
        return f"self.{wrong}"  # in a method, a name its instance has
    if not isinstance(wrong, str) or candidates is None or len(candidates) > MAX_CANDIDATES:
        return None
    if len(wrong) > MAX_NAME:
        return None
    best, best_distance = None, len(wrong)
    for candidate in candidates:
        if not isinstance(candidate, str) or candidate == wrong:
            continue
        limit = min((len(candidate) + len(wrong) + 3) * MOVE_COST // 6, best_distance - 1)
        found = distance(wrong, candidate, limit)
        if found <= limit and (best is None or found < best_distance):
            best, best_distance = candidate, found
    return best


def with_suggestion(last_line: str, exc: BaseException) -> str:
    """The traceback's last line (`NameError: ...\\n`) with Python's hint, unless it has one already."""
    name = suggestion(exc)
    if name is None or "Did you mean" in last_line:
        return last_line
    return last_line.rstrip("\n") + f". Did you mean: '{name}'?\n"


def _wrong_name_and_candidates(exc: BaseException) -> tuple[str | None, list | None]:
    if isinstance(exc, ImportError):
        wrong = getattr(exc, "name_from", None)  # (3.12)
        module_name = exc.name
        if wrong is None:
            found = _CANNOT_IMPORT.match(str(exc))
            if found is None:
                return None, None
            wrong, module_name = found.group(1), found.group(2)
        module = sys.modules.get(module_name or "")
        return wrong, None if module is None else dir(module)
    if isinstance(exc, AttributeError):
        if not hasattr(exc, "obj"):  # (raised by hand, without the object)
            return None, None
        return exc.name, dir(exc.obj)
    if isinstance(exc, NameError):
        tb = exc.__traceback__
        if tb is None:
            return None, None
        while tb.tb_next is not None:
            tb = tb.tb_next
        frame = tb.tb_frame
        if "self" in frame.f_locals and hasattr(frame.f_locals["self"], exc.name or ""):
            return exc.name, None  # (Python suggests `self.name` here: see suggestion)
        return exc.name, [*frame.f_locals, *frame.f_globals, *frame.f_builtins]
    return None, None


def distance(a: str, b: str, limit: int) -> int:
    """The edit distance from a to b (a letter's case 1, any other change 2) as CPython counts it, or
    more than limit as soon as it must be."""
    if a == b:
        return 0
    start = 0  # (common ends cost nothing)
    while start < min(len(a), len(b)) and a[start] == b[start]:
        start += 1
    end = 0
    while end < min(len(a), len(b)) - start and a[-1 - end] == b[-1 - end]:
        end += 1
    a, b = a[start : len(a) - end], b[start : len(b) - end]
    if not a or not b:
        return (len(a) + len(b)) * MOVE_COST
    if len(a) > MAX_NAME or len(b) > MAX_NAME:
        return limit + 1
    if len(b) < len(a):
        a, b = b, a
    if (len(b) - len(a)) * MOVE_COST > limit:
        return limit + 1
    row = [(i + 1) * MOVE_COST for i in range(len(a))]
    result = 0
    for j, b_char in enumerate(b):
        diagonal = result = j * MOVE_COST
        smallest = sys.maxsize
        for i, a_char in enumerate(a):
            substitute = diagonal + _substitution_cost(b_char, a_char)
            diagonal = row[i]
            result = min(min(result, diagonal) + MOVE_COST, substitute)
            row[i] = result
            smallest = min(smallest, result)
        if smallest > limit:
            return limit + 1
    return result


def _substitution_cost(a: str, b: str) -> int:
    if a == b:
        return 0
    if a.lower() == b.lower():
        return CASE_COST
    return MOVE_COST
