"""Sensors behave as the ev3dev drivers and python-ev3dev2 2.1.0 make them behave on a real EV3 (issue 12,
"Sensors"): each test runs a real python-ev3dev2 program on a simulated brick and checks what it printed.

References (read from the public sources):
- the lego-sensor class: lego-linux-drivers sensors/lego_sensor_class.c (value_show, bin_data_read);
  docs.ev3dev.org/projects/lego-linux-drivers/en/ev3dev-stretch/sensors.html
- the mode tables: lego-linux-drivers sensors/ev3_uart_sensor_defs.c and nxt_analog_sensor_defs.c, from which
  the "lego-ev3-color", "lego-ev3-us", "lego-ev3-gyro", "lego-ev3-ir", "lego-nxt-light" and "lego-nxt-sound"
  tables of docs.ev3dev.org/projects/lego-linux-drivers/en/ev3dev-stretch/sensor_data.html are generated
- python-ev3dev2 2.1.0 (ev3dev-lang-python, tag ev3dev-stretch/2.1.0): ev3dev2/sensor/__init__.py Sensor.value,
  ev3dev2/__init__.py Device._raise_friendly_access_error, ev3dev2/sensor/lego.py
"""

import errno

from ev3sim2d.world.robot_spec import default_robot
from tests.inline_world import arena

WALL_X = 19 * 12  # the face of the arena's right wall (20 cells of 12 cm)


def robot_file(tmp_path, sensors: str) -> str:
    """The default robot with other sensors, as a `robot:` line of a world file."""
    head, sensors_block = open(default_robot().source).read().split("\nsensors:\n")
    # the sensors are the file's last section
    assert all(line.startswith("  - ") for line in sensors_block.rstrip().splitlines())
    path = tmp_path / "robot.yaml"
    path.write_text(head + "\nsensors:\n" + sensors)
    return f"robot: {path}\n"


def lines(result) -> list[str]:
    assert result.status == "finished", (result.status, [line.text for line in result.trace.output])
    return [line.text for line in result.trace.output]


def test_changing_the_gyro_mode_resets_its_angle_and_modes_are_in_the_drivers_order(run):
    """ev3_uart_sensor_defs.c (LEGO_EV3_GYRO) lists the modes GYRO-ANG, GYRO-RATE, GYRO-FAS, GYRO-G&A,
    GYRO-CAL, TILT-RATE, TILT-ANG, and lego_sensor_class.c modes_show prints them in that order.  The gyro
    resets its angle when its mode changes, not when the mode it is in is written again: "To reset the gyro,
    you need to change it to a different mode and then back to the angle mode" (dlech, ev3dev/ev3dev#402);
    "When you read each value individually, the sensor switches modes, which resets the sensor"
    (ev3dev/ev3dev-lang-python#517: python-ev3dev2 2.1.0's `angle` and `rate` each _ensure_mode)."""
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import GyroSensor
        gyro = GyroSensor()
        print(" ".join(gyro.modes))
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on_for_degrees(20, -20, 200)
        print(gyro.angle)
        gyro.mode = "GYRO-ANG"  # the mode it is in: no reset
        print(gyro.angle)
        tank.on_for_degrees(20, -20, 200)
        print(gyro.angle)
        print(gyro.rate)  # GYRO-RATE: a change of mode
        print(gyro.angle)  # and back: counted from here
        tank.on_for_degrees(20, -20, 200)
        print(gyro.angle)
        print(gyro.angle_and_rate[0])  # GYRO-G&A: another change
        gyro.mode = "TILT-ANG"
        gyro.mode = "GYRO-ANG"
        print(gyro.angle)
    """)
    out = lines(result)
    assert out[0] == "GYRO-ANG GYRO-RATE GYRO-FAS GYRO-G&A GYRO-CAL TILT-RATE TILT-ANG"
    first, same_mode, second, rate, after_rate, third, after_g_a, after_tilt = map(int, out[1:])
    assert 80 < first < 105  # 200° of each wheel turns the base about 93° clockwise
    assert same_mode == first
    assert 2 * first - 5 <= second <= 2 * first + 5
    assert abs(rate) < 50  # standing still (or a sample from the last tick of the turn)
    assert after_rate == 0
    assert abs(third - first) <= 5
    assert after_g_a == 0 and after_tilt == 0


def test_ultrasonic_single_measurement_holds_until_the_mode_is_written_again(run):
    """ev3_uart_sensor_defs.c (LEGO_EV3_ULTRASONIC), US-SI-CM: "A measurement is taken when the mode is set and
    value0 will not change after this. To take another measurement set the mode again"; US-DIST-CM is a
    "Continuous measurement".  python-ev3dev2 2.1.0's distance_centimeters_ping writes the mode each time
    (`self.mode = self.MODE_US_SI_CM`), distance_centimeters_continuous only when it differs."""
    world = arena(start="x_cm: 100\n  y_cm: 120\n  heading_deg: 0")
    result = run(
        """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import UltrasonicSensor
        us = UltrasonicSensor()
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        print(us.distance_centimeters_ping)
        tank.on_for_rotations(30, 30, 1)
        print(us.value(0) / 10, us.mode)  # the same ping
        us.mode = "US-SI-CM"  # written again: a new ping
        print(us.value(0) / 10)
        print(us.distance_centimeters_continuous)
        tank.on_for_rotations(30, 30, 1)
        print(us.distance_centimeters_continuous)
        """,
        world,
    )
    out = lines(result)
    ping = float(out[0])
    held, mode = out[1].split()
    second_ping, continuous, continuous_later = float(out[2]), float(out[3]), float(out[4])
    assert ping == WALL_X - 108  # the sensor sits 8 cm ahead of the centre
    assert float(held) == ping and mode == "US-SI-CM"
    assert 14 < ping - second_ping < 20  # one rotation of a 5.6 cm wheel: 17.6 cm
    assert continuous == second_ping
    assert 14 < continuous - continuous_later < 20


def test_values_past_num_values_raise_the_drivers_error_and_raw_modes_and_formats_follow_the_drivers(
    run, tmp_path
):
    """lego_sensor_class.c value_show: `if (index < 0 || index >= lego_sensor_get_num_values(mode_info))
    return -ENXIO;` (value0..value7 always exist), and python-ev3dev2 2.1.0's Sensor.value(n) reads
    'value' + str(n) through Device._raise_friendly_access_error, which turns only EINVAL (ValueError) and
    ENODEV/ENOENT (DeviceNotFound) into other exceptions: ENXIO comes out as the OSError itself.

    ev3_uart_sensor_defs.c, LEGO_EV3_COLOR: REF-RAW has 2 s16 values, "ADC reading for LED on" then "ADC
    reading for LED off", and "Higher photodiode illumination will cause lower ADC measurements, so [...]
    reflect = value1 - value0"; RGB-RAW has 4 s16 values (red, green, blue, "ADC reading for LEDs off"); COL-CAL
    has num_values 3 (of 4 data sets), u16.  Formats: COL-REFLECT s8; LEGO_EV3_ULTRASONIC: the distances s16,
    US-LISTEN s8; LEGO_EV3_GYRO: s16; LEGO_EV3_INFRARED: IR-PROX, IR-SEEK, IR-REMOTE s8, IR-REM-A s16, IR-CAL s32
    (IR-REM-A reads 384 with no button pressed); nxt_analog_sensor_defs.c, LEGO_NXT_LIGHT_SENSOR and
    LEGO_NXT_SOUND_SENSOR: s32, and bin_data (bin_data_read copies the raw data) holds the unscaled millivolts
    that value0 scales ((raw - raw_min) * (si_max - si_min) / (raw_max - raw_min) + si_min)."""
    sensors = """  - {port: 1, kind: infrared, angle_deg: 0, radius_cm: 8, facing: forward}
  - {port: 2, kind: nxt-light, angle_deg: 0, radius_cm: 4, facing: down}
  - {port: 3, kind: color, angle_deg: 0, radius_cm: 7, facing: down, spot_cm: 1.5}
  - {port: 4, kind: ultrasonic, angle_deg: 0, radius_cm: 8, facing: forward, cone_deg: 15}
"""
    world = arena(start="x_cm: 100\n  y_cm: 120\n  heading_deg: 0", extra=robot_file(tmp_path, sensors))
    result = run(
        """
        from ev3dev2.sensor import Sensor, INPUT_1, INPUT_2, INPUT_3, INPUT_4
        from ev3dev2.sensor.lego import ColorSensor, UltrasonicSensor, InfraredSensor, LightSensor

        def show(sensor, mode):
            sensor.mode = mode
            values = [sensor.value(n) for n in range(sensor.num_values)]
            try:  # (value(8) is an IndexError in python-ev3dev2: it keeps 8 value handles)
                sensor.value(min(sensor.num_values, 7))
                past = "none"
            except OSError as err:
                past = "%s:%d" % (type(err).__name__, err.errno)
            print(mode, sensor.num_values, sensor.bin_data_format, past, *values)

        color = ColorSensor()
        print("reflect", color.reflected_light_intensity)
        try:
            color.value(5)
        except Exception as err:
            print("value5", type(err).__name__, err.errno)
        for mode in ("COL-REFLECT", "REF-RAW", "RGB-RAW", "COL-CAL"):
            show(color, mode)
        us = UltrasonicSensor()
        for mode in ("US-DIST-CM", "US-DIST-IN", "US-LISTEN", "US-SI-CM"):
            show(us, mode)
        ir = InfraredSensor()
        for mode in ("IR-PROX", "IR-SEEK", "IR-REMOTE", "IR-REM-A", "IR-CAL"):
            show(ir, mode)
        light = LightSensor()
        show(light, "REFLECT")
        print("bin_data", *light.bin_data("<i"))
        """,
        world,
    )
    out = lines(result)
    assert out[0] == "reflect 75"
    assert out[1] == f"value5 OSError {errno.ENXIO}"
    shown = {line.split()[0]: line.split()[1:] for line in out[2:-1]}
    past = f"OSError:{errno.ENXIO}"
    assert shown["COL-REFLECT"] == ["1", "s8", past, "75"]
    ref_on, ref_off = map(int, shown["REF-RAW"][3:])
    assert shown["REF-RAW"][:3] == ["2", "s16", past]
    assert ref_off - ref_on == 300  # reflect = value1 - value0: the red light of white paper
    assert shown["RGB-RAW"][:3] == ["4", "s16", past]
    red, green, blue, leds_off = map(int, shown["RGB-RAW"][3:])
    assert (red, green, blue) == (300, 290, 240) and leds_off == ref_off
    assert shown["COL-CAL"][:3] == ["3", "u16", past]
    assert shown["US-DIST-CM"][:3] == ["1", "s16", past]
    assert shown["US-DIST-IN"][:3] == ["1", "s16", past]
    assert shown["US-LISTEN"] == ["1", "s8", past, "0"]
    assert shown["US-SI-CM"][:3] == ["1", "s16", past]
    assert shown["IR-PROX"][:3] == ["1", "s8", past]
    assert shown["IR-SEEK"] == ["8", "s8", "none", *["0", "-128"] * 4]
    assert shown["IR-REMOTE"] == ["4", "s8", past, "0", "0", "0", "0"]
    assert shown["IR-REM-A"] == ["1", "s16", past, "384"]
    assert shown["IR-CAL"][:3] == ["2", "s32", past]
    reflect = int(shown["REFLECT"][3])
    assert shown["REFLECT"][:3] == ["1", "s32", past] and reflect == 612  # 20 + 0.55 x 75 %, in tenths
    (millivolts,) = map(int, out[-1].split()[1:])
    assert (millivolts - 4116) * 1000 // (543 - 4116) in (reflect - 1, reflect, reflect + 1)


def test_a_colour_sensor_facing_forward_reads_a_wall_by_its_distance_and_never_the_floor(run, tmp_path):
    """A forward-facing colour (or NXT light) sensor, as maze solvers use it for short distances: high within
    about 1 cm of a wall, falling to nothing by 10 cm (the curve and why: ev3sim2d/devices/color.py and
    docs/simulation.md).  The floor under it (black tape here, which a floor-reading sensor would read as 5)
    is not read.  COL-REFLECT is the LED-on less the LED-off reading (ev3_uart_sensor_defs.c, LEGO_EV3_COLOR,
    REF-RAW footnote), so nothing in front reads 0; the NXT light sensor has no such reference and reads its
    floor-less 20 %."""
    sensors = """  - {port: 1, kind: touch, angle_deg: 0, radius_cm: 9, facing: forward}        # front bumper
  - {port: 2, kind: nxt-light, angle_deg: 0, radius_cm: 8.5, facing: forward}
  - {port: 3, kind: color, angle_deg: 0, radius_cm: 8.5, facing: forward}
  - {port: 4, kind: ultrasonic, angle_deg: 0, radius_cm: 8, facing: forward, cone_deg: 15}
"""
    robot = robot_file(tmp_path, sensors)
    # every floor cell black tape: a sensor that read the floor would see 5
    black = ["#" + "k" * 18 + "#"] * 18
    program = """
        from ev3dev2.sensor.lego import ColorSensor, LightSensor
        color = ColorSensor()
        print(color.reflected_light_intensity, color.color, LightSensor().reflected_light_intensity)
    """
    readings = {}
    for gap_cm in (1, 2, 3, 5, 9.5, 30):
        x = WALL_X - 8.5 - gap_cm  # the sensors sit 8.5 cm ahead of the robot centre (its front: 9)
        world = arena(inner=black, start=f"x_cm: {x}\n  y_cm: 120\n  heading_deg: 0", extra=robot)
        reflect, colour, nxt = lines(run(program, world))[0].split()
        readings[gap_cm] = (int(reflect), int(colour), float(nxt))
    assert readings[1] == (75, 6, 61.2)  # white wall at 1 cm: as white paper under a downward sensor
    assert readings[2][0] == 18 and readings[2][1] == 6
    assert readings[3][0] == 8 and readings[3][1] == 0
    assert readings[5][0] == 2
    assert readings[9.5][0] == 0
    assert readings[30] == (0, 0, 20.0)  # nothing in front, and not the black floor (5)
    reflects = [readings[gap][0] for gap in (1, 2, 3, 5, 9.5, 30)]
    assert reflects == sorted(reflects, reverse=True)
