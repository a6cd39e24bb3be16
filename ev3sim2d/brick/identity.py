"""Objects of the program's own classes hash and print the same in every run.

CPython hashes an object that does not define `__hash__` by its memory address, and prints it
as `<Node object at 0x7f3a...>`.  Addresses change from run to run (address space layout,
allocation history, how the brick's messages happen to arrive), so a program that iterates
over a set of its own objects (a maze solver's set of nodes), or prints one, would do something
else in each run.  Inside a brick, every class that a module of the program defines (a file in the
program's folders) and that keeps `object`'s hash or repr gets instead:
- `__hash__`: a number given when the object is first hashed, counting up in the order the
  program hashes its objects: the same order in every run, so sets and dicts of such objects
  iterate the same way (equality stays identity, as before);
- `__repr__`: the same text with that number where the address was.
Classes of the standard library and of third-party packages are left as they are: only what
the program defines.  Objects of built-in types hashed by address (`object()`) stay left to chance.
"""

from __future__ import annotations

import builtins
import itertools
import weakref

_real_build_class = builtins.__build_class__
_hash_of_object = object.__hash__
_repr_of_object = object.__repr__
_numbers = itertools.count(1)
_given: dict[int, int] = {}  # id(obj) -> its number, while obj lives


def _number(obj) -> int:
    key = id(obj)
    number = _given.get(key)
    if number is None:
        number = _given[key] = next(_numbers)
        try:
            weakref.finalize(obj, _given.pop, key, None)
        except TypeError:  # no weak references (a class with __slots__): keep the number
            pass
    return number


def _stable_hash(self) -> int:
    return _number(self)


def _stable_repr(self) -> str:
    cls = type(self)
    return f"<{cls.__module__}.{cls.__qualname__} object at {0x10000 + 16 * _number(self):#x}>"


def install(program_dirs: list[str]) -> None:
    """From now on, classes defined by modules under program_dirs hash and print by number."""
    folders = tuple(d.rstrip("/") + "/" for d in program_dirs)

    def build_class(func, name, *bases, **kwargs):
        cls = _real_build_class(func, name, *bases, **kwargs)
        source = getattr(func, "__code__", None)
        filename = source.co_filename if source is not None else ""
        if isinstance(cls, type) and filename.startswith(folders):
            if cls.__hash__ is _hash_of_object:
                cls.__hash__ = _stable_hash
            if cls.__repr__ is _repr_of_object:
                cls.__repr__ = _stable_repr
        return cls

    builtins.__build_class__ = build_class
