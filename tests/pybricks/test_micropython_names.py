"""MicroPython's module names, as EV3 MicroPython programs import them (pybricks/_micropython/).

Firmware: pybricks-micropython v2.0.0 (MicroPython v1.11, micropython-tag), bricks/ev3dev/mpconfigport.h:
MICROPY_PY_UTIME (utime, with extmod/utime_mphal.c's ticks), MICROPY_PY_UERRNO and its
MICROPY_PY_UERRNO_LIST, MICROPY_PY_URANDOM with MICROPY_PY_URANDOM_EXTRA_FUNCS, MICROPY_PY_UJSON,
ustruct, uos, ucollections, uio, ubinascii, uhashlib, ure, uheapq, uselect, uzlib, and `micropython`.
A brick puts the folder on the path of a program that is not python-ev3dev2's (ev3sim2d/brick/run.py).
"""

import errno


def printed(result) -> list[str]:
    assert result.status == "finished", (result.reason, result.error)
    return [line.text for line in result.trace.output if line.stream == "stdout"]


def test_a_pybricks_program_imports_micropythons_modules(run):
    """mpconfigport.h's modules import under their MicroPython names; uerrno's ENODEV is the errno of the
    OSError a missing sensor raises (pbdevice.c: ENODEV), so `e.args[0] == ENODEV` works as on a brick;
    micropython.const(x) is x."""
    out = printed(
        run(
            """
            from pybricks.ev3devices import TouchSensor
            from pybricks.parameters import Port
            from uerrno import ENODEV, EINVAL, errorcode
            import utime, urandom, ujson, ustruct, uos, ucollections, uio, ubinascii, uhashlib, ure, uheapq
            import uselect, uzlib
            from micropython import const
            X = const(42)
            try:
                TouchSensor(Port.S4)
            except OSError as e:
                print(e.args[0] == ENODEV, errorcode[ENODEV], EINVAL)
            print(X, ujson.dumps({"a": [1, 2]}), ustruct.unpack("<h", ustruct.pack("<h", -2)))
            print(ubinascii.hexlify(b"ev3"), ure.match("a+", "aab").group(0), type(uos.listdir(".")).__name__)
            """
        )
    )
    assert out == [f"True ENODEV {errno.EINVAL}", '42 {"a": [1, 2]} (-2,)', "b'657633' aa list"]


def test_utime_ticks_follow_the_virtual_clock_and_wrap(run):
    """extmod/utime_mphal.c: ticks_ms/us are the monotonic clock masked to MICROPY_PY_UTIME_TICKS_PERIOD
    (2**30 on the EV3's 32-bit small ints); ticks_diff(a, b) is the signed difference across a wrap and
    ticks_add(t, d) wraps; sleep_ms waits in ms, sleep in s."""
    out = printed(
        run(
            """
            from utime import ticks_ms, ticks_us, ticks_diff, ticks_add, sleep_ms, sleep
            start = ticks_ms()
            sleep_ms(250)
            sleep(0.5)
            print(ticks_diff(ticks_ms(), start))
            top = 2**30 - 5
            print(ticks_add(top, 10), ticks_diff(ticks_add(top, 10), top), ticks_diff(3, 2**30 - 3))
            print(ticks_ms() < 2**30, ticks_us() < 2**30)
            """
        )
    )
    assert out == ["750", "5 10 6", "True True"]


def test_urandom_repeats_from_run_to_run(run):
    """MICROPY_PY_URANDOM_EXTRA_FUNCS: getrandbits, seed, randrange, randint, choice, random, uniform.  On a
    brick the numbers are seeded from ticks_us (MICROPY_PY_URANDOM_SEED_INIT_FUNC); in a simulated run
    they come from the program's seeded random, so a run repeats; getrandbits takes 1 to 32 bits."""
    program = """
        import urandom
        print(urandom.getrandbits(8), urandom.randint(1, 6), urandom.choice("abc"), urandom.random() < 1)
        urandom.seed(7)
        a = urandom.randrange(100)
        urandom.seed(7)
        print(a == urandom.randrange(100), 2 <= urandom.uniform(2, 3) <= 3)
        try:
            urandom.getrandbits(33)
        except ValueError:
            print("ValueError")
    """
    first, second = printed(run(program)), printed(run(program))
    assert first == second
    assert first[1:] == ["True True", "ValueError"]


def test_an_ev3dev2_program_does_not_get_micropythons_names(run):
    """The folder is for Pybricks programs only: an ev3dev brick's Python has no utime (python-ev3dev2
    programs run under CPython 3.5 on ev3dev), so `import utime` there is an ImportError."""
    out = printed(
        run(
            """
            from ev3dev2.sound import Sound
            try:
                import utime
                print("utime")
            except ImportError:
                print("ImportError")
            """
        )
    )
    assert out == ["ImportError"]
