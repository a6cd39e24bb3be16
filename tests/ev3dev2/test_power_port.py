"""PowerSupply and LegoPort: plain attribute devices."""

import pytest

from ev3dev2.port import LegoPort
from ev3dev2.power import PowerSupply
from ev3dev2.sensor import INPUT_1

from .fake_brick import battery, lego_port


def test_battery(make_brick):
    make_brick(battery())
    power = PowerSupply()

    assert power.measured_volts == pytest.approx(7.85)
    assert power.measured_amps == pytest.approx(0.18)
    assert (power.max_voltage, power.min_voltage) == (9000000, 6000000)
    assert (power.technology, power.type) == ("Li-ion", "Battery")


def test_lego_port_modes(make_brick):
    brick = make_brick(lego_port("port0", "in1"), lego_port("port1", "in2"))
    port = LegoPort(INPUT_1)

    assert port.mode == "auto"
    assert "ev3-uart" in port.modes
    port.mode = "nxt-analog"
    port.set_device = "lego-nxt-touch"
    with pytest.raises(Exception, match="^set_device is a write-only property!$"):
        _ = port.set_device
    assert port.address == "ev3-ports:in1"
    assert brick.writes() == [("port0", "mode", "nxt-analog"), ("port0", "set_device", "lego-nxt-touch")]
