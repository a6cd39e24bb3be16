"""Finding the device on a port, as Pybricks 2.0 does when a device object is made.

The firmware looks for the device on the port's ev3dev address (lib/ev3dev/src/ev3dev_stretch/
lego_sensor.c and lib/pbio/drv/ev3dev_stretch/motor.c) and raises OSError with ENODEV when nothing
of the right kind is there ("OSError: [Errno 19] ENODEV" on the brick).  A sensor class given a motor
port, or a motor class given a sensor port, raises ValueError before looking (pb_assert with
PBIO_ERROR_INVALID_PORT in pbdevice.c and pb_type_motor).
"""

from errno import ENODEV

from . import _link
from .parameters import Port

MOTOR_PORTS = {Port.A: "outA", Port.B: "outB", Port.C: "outC", Port.D: "outD"}
SENSOR_PORTS = {Port.S1: "in1", Port.S2: "in2", Port.S3: "in3", Port.S4: "in4"}


def port_name(port, motor: bool) -> str:
    """'outA' for Port.A when a motor is wanted, 'in1' for Port.S1 when a sensor is; ValueError else."""
    ports = MOTOR_PORTS if motor else SENSOR_PORTS
    if port in ports:
        return ports[port]
    if port in MOTOR_PORTS or port in SENSOR_PORTS:
        raise ValueError("Invalid argument")
    raise TypeError("port must be a Port, e.g. Port.A or Port.S1")


def find(port, class_name: str, drivers: tuple, motor: bool = False) -> str:
    """The sysfs name of the device of one of `drivers` on `port`; OSError(ENODEV) if there is none."""
    name = port_name(port, motor)
    found = _link.list_device_names(class_name, "*", address="ev3-ports:" + name)
    for device in found:
        if _link.read(class_name, device, "driver_name") in drivers:
            return device
    raise OSError(
        ENODEV, f"ENODEV: no {' or '.join(drivers)} on {port} ({name}); check the robot file's ports"
    )
