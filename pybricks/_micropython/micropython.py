"""MicroPython's `micropython` module as EV3 MicroPython (MicroPython v1.11) has it.

`const(x)` is x (the compiler's constant folding is an optimisation only); the memory reports print
a line, as there is no MicroPython heap here.  `native` and `viper` leave a function as it is (on the
brick they are compiler decorators that make it machine code)."""


def const(value):
    """The value itself: on the brick, names made with const() are folded into the code."""
    return value


_opt_level = 0


def opt_level(level=None):
    """The optimisation level of compiling (0 to 3); with a level, set it."""
    global _opt_level
    if level is None:
        return _opt_level
    _opt_level = int(level)
    return None


def mem_info(verbose=None):
    """Print a report on memory (here: that there is no MicroPython heap to report on)."""
    print("mem: no MicroPython heap in the simulator (CPython manages memory)")


def qstr_info(verbose=None):
    """Print a report on interned strings (here: none to report on)."""
    print("qstr: no MicroPython qstr pool in the simulator")


def stack_use():
    """How much of the stack is in use, in bytes (here always 0)."""
    return 0


def heap_lock():
    """Lock the heap (a no-op here)."""


def heap_unlock():
    """Unlock the heap (a no-op here)."""


def alloc_emergency_exception_buf(size):
    """Set aside memory for exceptions raised in interrupts (a no-op here)."""


def kbd_intr(chr):
    """Choose the character that raises KeyboardInterrupt (a no-op here)."""


def schedule(func, arg):
    """Run func(arg) "soon": here at once."""
    func(arg)


def native(func):
    """Leave `func` as it is (on the brick: compile it to machine code)."""
    return func


viper = native
