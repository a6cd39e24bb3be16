"""The time a program spends computing, on the virtual clock (see scheduler.py, `charge`).

The EV3's 300 MHz ARM runs Python far slower than a PC: a loop that never touches a device or the clock
still takes time on a brick, and a busy-wait on `time.time()` ends when its time is up.  Each line of the
program's own code costs LINE_US, counted by the code itself (`Lines`), charged to the running task in
slices of scheduler.SWITCH_US.
"""

from __future__ import annotations

import ast
import builtins
import os
import sys
import types
from _thread import get_ident
from importlib.machinery import PathFinder, SourceFileLoader

from .program_kind import ProgramKind
from .scheduler import SWITCH_US, Scheduler

# What a line of a program's own code costs the brick, in virtual microseconds.  Measured on an EV3 with
# python-ev3dev2 2.1.0 (ev3dev-lang-python, utils/benchmarking/benchmark-results.md, ev3dev-stretch
# 2019-05-29, Python 3.5): `python3 -m timeit "m.count_per_rot"`, a cached property that does no I/O,
# "1000 loops, best of 3: 215 usec per loop".  One such loop runs 8 lines (timeit's loop, the property,
# get_cached_attr_int), as CpuTime counts them and as sys.settrace does: 215 / 8 = 27 us a line.
LINE_US = 27


class CpuTime:
    """The time a program spends computing, on the virtual clock: LINE_US for each line of its own code.

    The program's own code is what its files define (those under its folders, as brick/identity.py counts
    them), never the brick's, the shims', Python's nor third parties': what the shim does for a device
    costs what a device access costs (brick/link.py), once.  Its lines are counted by the code itself:
    each file of the program is compiled with a call before each of its statements, each time round a
    loop (a `while` loop's test, a `for` loop's next item, a comprehension's) and in each call of a lambda
    (`Lines`); its modules are imported so compiled (`find_spec`).  So a line is a statement, or a loop
    going round: what sys.settrace calls a line when each statement has a line of its own.  Nothing else
    is slowed down: sys.settrace would make every line of the shim and of the brick in the program's
    threads 3 to 4 times slower on Python 3.11, sys.monitoring exists from 3.12 only, and both count
    lines a little differently from one Python to the next; the statements of a source are the same on
    every Python, so the same program spends the same time on all of them.  Code the program makes
    from text (exec, eval) is not its files': it computes for free."""

    LINE = "__ev3sim2d_line__"  # the function called before each statement (in builtins)

    def __init__(
        self, scheduler: Scheduler, folders: list[str], outside: list[str], kind: ProgramKind | None = None
    ) -> None:
        """folders: the program's; outside: folders within them that are not the program's (the shims);
        kind: checks that each module of the program imports the program's shim (program_kind.py)."""
        self.scheduler = scheduler
        self.kind = kind
        self.folders = tuple(_folder(f) for f in folders)
        self.outside = tuple(_folder(f) for f in outside)
        self._mine: dict[str, bool] = {}  # file name -> whether it is the program's
        scheduler.program_file = self.is_program

    def is_program(self, filename: str) -> bool:
        mine = self._mine.get(filename)
        if mine is None:
            mine = self._mine[filename] = filename.startswith(self.folders) and not filename.startswith(
                self.outside
            )
        return mine

    def install(self) -> None:
        """Count from now on: the line function in builtins, and the program's modules imported counted."""
        scheduler = self.scheduler
        charge = scheduler.charge

        def line() -> bool:
            task = scheduler.current
            if task is not None and task.thread_id == get_ident():  # (not a finalizer in a brick's thread)
                task.cpu_us += LINE_US
                if task.cpu_us >= SWITCH_US:
                    charge(task)
            return True

        setattr(builtins, self.LINE, line)
        sys.meta_path.insert(0, self)

    def compile(self, source: bytes | str, filename: str) -> types.CodeType:
        """A file of the program, compiled to count its lines (SyntaxError as compile() raises it)."""
        tree = Lines(self.LINE).visit(ast.parse(source, filename))
        return compile(ast.fix_missing_locations(tree), filename, "exec", dont_inherit=True)

    def find_spec(self, name: str, path=None, target=None):
        """(a meta path finder) A module of the program's own, to be loaded counted; None for any other."""
        where = list(self.folders) if path is None else [p for p in path if self.is_program(_folder(p))]
        if not where:
            return None
        spec = PathFinder.find_spec(name, where)
        if spec is None or not isinstance(spec.loader, SourceFileLoader) or not self.is_program(spec.origin):
            return None
        spec.loader = _CountedLoader(spec.loader.name, spec.loader.path, self)
        return spec


class _CountedLoader(SourceFileLoader):
    """Loads a module of the program compiled to count its lines, always from its source (a cached .pyc
    would be the module without the counting; none is written)."""

    def __init__(self, fullname: str, path: str, cpu: CpuTime) -> None:
        super().__init__(fullname, path)
        self.cpu = cpu

    def get_code(self, fullname: str) -> types.CodeType:
        code = self.cpu.compile(self.get_data(self.path), self.path)
        mixed = self.cpu.kind.check(code, self.path) if self.cpu.kind is not None else None
        if mixed is not None:
            raise ImportError(mixed[1], name=fullname, path=self.path)
        return code


class Lines(ast.NodeTransformer):
    """Puts a call of `line` before each statement (after a docstring and `from __future__` imports), in
    each loop's test or first statement, in each comprehension's filters and in each lambda's body.  The
    calls bear their statement's place, so that a traceback through one shows the statement's line."""

    DOCUMENTED = (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)

    def __init__(self, line: str) -> None:
        self.line = line

    def _call(self, at: ast.AST) -> ast.Call:
        return ast.copy_location(ast.Call(ast.Name(self.line, ast.Load()), [], []), at)

    def _and(self, at: ast.expr) -> ast.BoolOp:
        return ast.copy_location(ast.BoolOp(ast.And(), [self._call(at), at]), at)  # line() is True

    def generic_visit(self, node: ast.AST) -> ast.AST:
        super().generic_visit(node)
        for field in ("body", "orelse", "finalbody"):
            statements = getattr(node, field, None)
            if type(statements) is list and statements and isinstance(statements[0], ast.stmt):
                documented = field == "body" and isinstance(node, self.DOCUMENTED)
                setattr(node, field, self._counted(statements, documented))
        if isinstance(node, (ast.For, ast.AsyncFor)):  # (the for line, each item)
            node.body.insert(0, ast.copy_location(ast.Expr(self._call(node)), node))
        elif isinstance(node, ast.While):
            node.test = self._and(node.test)  # (the statement itself is not counted: its test is, each time)
        elif isinstance(node, ast.comprehension):
            node.ifs.insert(0, self._call(node.iter))
        elif isinstance(node, ast.Lambda):
            node.body = self._and(node.body)
        return node

    def _counted(self, statements: list[ast.stmt], documented: bool) -> list[ast.stmt]:
        counted = []
        for i, statement in enumerate(statements):
            first = (
                documented
                and i == 0
                and isinstance(statement, ast.Expr)
                and isinstance(statement.value, ast.Constant)
                and isinstance(statement.value.value, str)
            )
            future = isinstance(statement, ast.ImportFrom) and statement.module == "__future__"
            if not (first or future or isinstance(statement, ast.While)):
                counted.append(ast.copy_location(ast.Expr(self._call(statement)), statement))
            counted.append(statement)
        return counted


def _folder(path: str) -> str:
    return os.path.join(path, "")  # (with its separator: /a/b is not /a/bc)
