"""The EV3 touch sensor as its driver describes it.

lego-linux-drivers, sensors/ev3_analog_sensor_defs.c, LEGO_EV3_TOUCH_SENSOR: one mode, "TOUCH",
`.data_sets = 1`, `.data_type = LEGO_SENSOR_DATA_S32` (so `bin_data_format` reads `s32`, and
`bin_data` holds one 4-byte little-endian integer), value0 0 (released) or 1 (pressed).  What that
integer holds on a brick (pin 6's millivolts, which the driver's scale turns into value0 with
`raw_value > 250`) is a known difference: docs/fidelity.md, lego-ev3-touch-bin-data.
"""

from tests.inline_world import arena


def test_bin_data_is_one_s32_and_value0_says_pressed(run):
    result = run(
        """
        import struct
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import TouchSensor
        touch = TouchSensor()
        print(touch.bin_data_format, touch.num_values, len(touch.bin_data()), len(touch.bin_data("<i")))
        print(touch.value(), touch.is_pressed)
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(30, 30)
        touch.wait_for_pressed()
        tank.off()
        print(touch.value(), touch.is_pressed, len(struct.unpack("<i", touch.bin_data())))
    """,
        arena(width=8, height=8, start="x_cm: 30\n  y_cm: 48\n  heading_deg: 0"),
    )
    assert result.status == "finished", result.reason
    assert [line.text for line in result.trace.output] == [
        "s32 1 4 1",
        "0 0",
        "1 1 1",
    ]  # (is_pressed is value(0): an int in 2.1.0)
