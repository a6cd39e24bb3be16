"""pybricks.tools in simulated runs: wait, StopWatch and DataLog as Pybricks 2.0 has them.

Firmware: pybricks-micropython v2.0.0, extmod/modtools.c (wait, StopWatch, in whole ms of
mp_hal_ticks_ms) and bricks/ev3dev/modules/pybricks/tools.py (DataLog, and print for 1.0 programs).
"""

import re


def printed(result) -> list[str]:
    assert result.status == "finished", (result.reason, result.error)
    return [line.text for line in result.trace.output if line.stream == "stdout"]


def test_wait_truncates_floats_and_ignores_negative_times(run):
    """modtools.c tools_wait: the time is pb_obj_get_int'd (py/pbobj.c: a float is cast to an int, toward
    zero), and only a duration > 0 is waited (mp_hal_delay_ms), so wait(0.9) and wait(-5) return at once
    and wait(2.7) waits 2 ms; wait(time=...) is its keyword."""
    out = printed(
        run(
            """
            from utime import ticks_us
            from pybricks.tools import wait
            times = []
            for ms in (0.9, -5, -0.5, 2.7, 10):
                start = ticks_us()
                wait(ms)
                times.append(ticks_us() - start)
            start = ticks_us()
            wait(time=25)
            times.append(ticks_us() - start)
            print(times)
            try:
                wait("1")
            except TypeError:
                print("TypeError")
            """
        )
    )
    assert out == ["[0, 0, 0, 2000, 10000, 25000]", "TypeError"]


def test_stopwatch_counts_ms_and_pauses(run):
    """modtools.c StopWatch: starts running when made; time() is ticks - start - time spent pausing;
    pause() freezes it, resume() counts on from there; reset() sets it to 0 and a paused stopwatch stays
    paused (time_stop = time_start, running unchanged)."""
    out = printed(
        run(
            """
            from pybricks.tools import StopWatch, wait
            watch = StopWatch()
            times = []
            wait(300)
            times.append(watch.time())
            watch.pause()
            wait(200)
            times.append(watch.time())
            watch.resume()
            wait(100)
            times.append(watch.time())
            watch.pause()
            watch.reset()
            wait(50)
            times.append(watch.time())
            watch.resume()
            wait(70)
            times.append(watch.time())
            print(times)
            """
        )
    )
    assert out == ["[300, 300, 400, 0, 70]"]


def test_datalog_writes_the_firmwares_csv(run):
    """bricks/ev3dev/modules/pybricks/tools.py DataLog: the file is name + '_yyyy_mm_dd_hh_mm_ss_uuuuuu' (the
    local time and ticks_us() % 1000000) + '.' + extension in the program's folder; the headers are its
    first line, values are printed with sep=', '; repr() reads the whole file back.  The clock is the
    virtual one: a run starts at 2025-01-01 00:00:00, so a log made 1.5 s in is stamped 00_00_01."""
    out = printed(
        run(
            """
            import os
            from pybricks.tools import DataLog, wait
            wait(1500)
            data = DataLog("time", "angle")
            data.log(0, 1.5)
            data.log(10, -2, "x")
            print(sorted(f for f in os.listdir(".") if f.endswith(".csv")))
            print(repr(data), end="")
            """
        )
    )
    assert re.fullmatch(r"\['log_2025_01_01_00_00_01_5\d{5}\.csv'\]", out[0]), out[0]
    assert out[1:] == ["time, angle", "0, 1.5", "10, -2, x"]


def test_datalog_headers_only_into_an_empty_file_and_append(run):
    """tools.py DataLog: timestamp=False names the file name.extension; append=True opens it 'a+' and
    writes the headers only when the file is empty (length == 0), so a second log appends its rows under
    the first one's headers; without append the file is made anew ('w+')."""
    out = printed(
        run(
            """
            from pybricks.tools import DataLog
            first = DataLog("a", "b", name="run", timestamp=False, extension="txt", append=True)
            first.log(1, 2)
            second = DataLog("a", "b", name="run", timestamp=False, extension="txt", append=True)
            second.log(3, 4)
            print(open("run.txt").read(), end="")
            print("--")
            fresh = DataLog(name="run", timestamp=False, extension="txt")
            fresh.log(5)
            print(repr(fresh), end="")
            """
        )
    )
    assert out == ["a, b", "1, 2", "3, 4", "--", "5"]


def test_print_is_importable_from_tools_for_1_0_programs(run):
    """tools.py: `from builtins import print`, for compatibility with EV3 MicroPython 1.0."""
    out = printed(
        run(
            """
            from pybricks.tools import print as tools_print
            tools_print("hello", 1, sep="-")
            print(tools_print is print)
            """
        )
    )
    assert out == ["hello-1", "True"]
