"""Which shim a program asks for, python-ev3dev2 or Pybricks, read from the imports its files make.

Both shims are on a brick's path, so `ev3sim2d run main.py` runs either kind of program as it is.  No
EV3 runs a program that uses both: an ev3dev brick has no `pybricks`, and LEGO's EV3 MicroPython image
runs its programs with pybricks-micropython, which has no `ev3dev2`.  So the first file that imports
one decides, and a file of the program that imports the other is an ImportError at that import, naming
both places and the fix.  The imports are read from the compiled code (every IMPORT_NAME, in nested
functions too), so the check costs nothing while the program runs.
"""

from __future__ import annotations

import dis
import os
import types

SHIMS = ("ev3dev2", "pybricks")


def shim_imports(code: types.CodeType) -> list[tuple[str, int]]:
    """(shim, line) for each import of a shim's module in `code` and the code nested in it, in order."""
    found: list[tuple[str, int]] = []
    stack = [code]
    while stack:
        co = stack.pop()
        starts = sorted((offset, line) for offset, line in dis.findlinestarts(co) if line is not None)
        line, i = co.co_firstlineno, 0
        for instruction in dis.get_instructions(co):
            while i < len(starts) and starts[i][0] <= instruction.offset:
                line = starts[i][1]
                i += 1
            if instruction.opname == "IMPORT_NAME":
                top = str(instruction.argval).split(".")[0]
                if top in SHIMS:
                    found.append((top, line))
        stack.extend(c for c in reversed(co.co_consts) if isinstance(c, types.CodeType))
    return sorted(found, key=lambda item: item[1])


class ProgramKind:
    """The shim a program uses, decided by the first of its files that imports one."""

    def __init__(self) -> None:
        self.shim: str | None = None
        self.where: tuple[str, int] | None = None  # (file, line) of the import that decided

    def check(self, code: types.CodeType, filename: str) -> tuple[int, str] | None:
        """None if the file's imports agree with the program's; else (line, message) of the first that
        does not."""
        for shim, line in shim_imports(code):
            if self.shim is None:
                self.shim, self.where = shim, (filename, line)
            elif shim != self.shim:
                return line, self.mixed(shim, filename, line)
        return None

    def mixed(self, shim: str, filename: str, line: int) -> str:
        first_file, first_line = self.where
        return (
            f"{os.path.basename(filename)}, line {line}, imports {shim}, and {os.path.basename(first_file)}, "
            f"line {first_line}, imports {self.shim}: a program runs with one of them, as an EV3 runs either "
            "python-ev3dev2 (ev3dev) or Pybricks (LEGO's EV3 MicroPython), never both; keep the imports of "
            "one (docs/pybricks.md)"
        )
