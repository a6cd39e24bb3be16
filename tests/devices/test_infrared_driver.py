"""The EV3 infrared sensor's IR-SEEK mode as its driver documents it.

lego-linux-drivers, sensors/ev3_uart_sensor_defs.c, LEGO_EV3_INFRARED mode 1 "IR-SEEK": `.data_sets = 8`,
`LEGO_SENSOR_DATA_S8`, units "pct"; @value0, 2, 4, 6: a channel's heading "(-25 to 25)", @value1, 3, 5,
7: its distance "(-128 and 0 to 100)", -128 when that channel has no beacon.  So no value is above 100
(docs/fidelity.md compares every mode's range with its driver's).
"""

import struct

from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.robot_spec import parse_robot
from tests.inline_world import arena, two_wheel_robot


def infrared_sensor():
    world = arena()
    robot = parse_robot(
        two_wheel_robot("ir", "{port: 1, kind: infrared, angle_deg: 0, radius_cm: 8, facing: forward}")
    )
    sim = Simulation(world, [("robot", robot, world.start)])
    return sim.robots[0], sim.robots[0].sensors["in1"]


def test_ir_seek_reports_no_beacon_on_each_of_the_four_channels():
    _, sensor = infrared_sensor()
    sensor.write("mode", "IR-SEEK")
    assert (sensor.read("num_values"), sensor.read("bin_data_format"), sensor.read("units")) == (
        "8",
        "s8",
        "pct",
    )
    values = [int(sensor.read(f"value{n}")) for n in range(8)]
    assert values == [0, -128] * 4
    assert struct.unpack("<8b", sensor.read("bin_data").encode("latin-1")) == tuple(values)


def test_ir_seek_values_stay_within_the_documented_minus_128_to_100():
    robot, sensor = infrared_sensor()
    sensor.write("mode", "IR-SEEK")
    sensor.measure = lambda mode: (120.0,) * 8  # a beacon model that overshoots is held to the driver's range
    robot.tick += 1
    assert [int(sensor.read(f"value{n}")) for n in range(8)] == [100] * 8
