#!/usr/bin/env pybricks-micropython
"""Other devices: an NXT Light Sensor, any sensor read by its ev3dev mode, a motor by duty cycle alone, and
a program that copes with a sensor that is not there (OSError with ENODEV, as on a brick).

Try it:  ev3sim2d run examples/pybricks/other_devices.py --maze line
         ev3sim2d run examples/pybricks/other_devices.py --maze line --robot examples/robots/nxt-light-base.yaml
"""

from uerrno import ENODEV

from pybricks.iodevices import DCMotor, Ev3devSensor
from pybricks.nxtdevices import LightSensor
from pybricks.parameters import Port
from pybricks.tools import wait

try:
    light = LightSensor(Port.S1)  # the shipped robot has a touch sensor there: ENODEV
    print("NXT light sensor: reflection", light.reflection(), "ambient", light.ambient())
except OSError as error:
    if error.args[0] != ENODEV:
        raise
    print("no NXT light sensor on S1")

eye = Ev3devSensor(Port.S3)  # the colour sensor, read as ev3dev names its modes
print("COL-REFLECT", eye.read("COL-REFLECT"), "RGB-RAW", len(eye.read("RGB-RAW")), "values")

arm = DCMotor(Port.A)  # the medium motor, without its encoder
arm.dc(40)
wait(500)
arm.brake()
print("arm done")
