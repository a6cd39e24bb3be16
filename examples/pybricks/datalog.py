#!/usr/bin/env pybricks-micropython
"""Tools: a StopWatch times a drive, and a DataLog writes the wheel's angle against time to a CSV file.

The file is log.csv, in the program's folder on the brick (`ev3sim2d run` leaves it beside the program);
the program prints it at the end, as print(data) shows it on an EV3.

Try it:  ev3sim2d run examples/pybricks/datalog.py --maze empty
"""

from pybricks.ev3devices import Motor
from pybricks.parameters import Port
from pybricks.tools import DataLog, StopWatch, wait

wheel = Motor(Port.B)
data = DataLog("time", "angle", name="log", timestamp=False)  # log.csv, with these column headers
watch = StopWatch()

wheel.run(360)  # one turn a second
while watch.time() < 1000:
    data.log(watch.time(), wheel.angle())
    wait(100)
wheel.stop()
print("took", watch.time(), "ms")
print(data)
