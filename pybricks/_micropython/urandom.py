"""MicroPython's `urandom` as EV3 MicroPython (MicroPython v1.11, with its extra functions) has it.

The numbers come from the program's `random` (seeded by the brick, so a run repeats), not from
MicroPython's yasmarang generator: the same calls give other numbers than on a brick."""

import random as _random


def getrandbits(n):
    """An int of `n` random bits, 1 to 32."""
    if n <= 0 or n > 32:
        raise ValueError("bits must be 32 or less")
    return _random.getrandbits(n)


def seed(n):
    """Start the numbers again from `n`."""
    _random.seed(n)


def randrange(start, stop=None, step=1):
    """A random int from range(start, stop, step)."""
    return _random.randrange(start, stop, step)


def randint(a, b):
    """A random int from a to b, both included."""
    return _random.randint(a, b)


def choice(sequence):
    """A random item of a non-empty sequence."""
    if not sequence:
        raise IndexError
    return _random.choice(sequence)


def random():
    """A random float from 0.0 to 1.0 (1.0 excluded)."""
    return _random.random()


def uniform(a, b):
    """A random float from a to b."""
    return _random.uniform(a, b)
