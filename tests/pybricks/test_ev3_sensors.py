"""The EV3 sensors of pybricks.ev3devices behave as on an EV3 with pybricks-micropython v2.0.0.

Sources (pybricks-micropython, tag v2.0.0): extmod/modev3devices.c (what each method reads and returns),
bricks/ev3dev/pbdevice.c (get_values: the mode is written only when a method needs another one, then
num_values and bin_data_format are read and the sensor's switch delay waited; every call reads bin_data
once; get_mode_switch_delay: colour 30 ms, infrared 1100 ms), lib/ev3dev/src/ev3dev_stretch/lego_sensor.c
(which driver each class accepts), py/pberror.c pb_assert (ENODEV -> OSError, INVALID_ARG/PORT ->
ValueError).  Each test runs a program in a simulated world and checks what it printed.
"""

from tests.inline_world import arena, robot_file

# a 12 cm grid with one black column (col 5: x 60..72) on white floor
STRIPE = ["#" + "...." + "k" + "." * 13 + "#"] * 18


def printed(result):
    assert result.status == "finished", (result.reason, result.error)
    return [line.text for line in result.trace.output]


def at(x_cm, heading_deg=0, inner=None, robot=None, **kwargs):
    extra = f"robot: {robot}\n" if robot else ""
    return arena(
        inner=inner, start=f"x_cm: {x_cm}\n  y_cm: 120\n  heading_deg: {heading_deg}", extra=extra, **kwargs
    )


# ------------------------------------------------------------------------------------- ColorSensor


def test_reflection_and_ambient_are_ints_dark_on_the_line_and_light_beside_it(run):
    """ColorSensor.reflection() is COL-REFLECT's value and ambient() COL-AMBIENT's, as ints 0-100
    (modev3devices.c ev3devices_ColorSensor_reflection, ev3devices_ColorSensor_ambient: mp_obj_new_int of
    the raw reading).  The default robot's colour sensor is 7 cm ahead of its centre."""
    program = """
        from pybricks.ev3devices import ColorSensor
        from pybricks.parameters import Port
        sensor = ColorSensor(Port.S3)
        r, a = sensor.reflection(), sensor.ambient()
        print(r, type(r).__name__, a, type(a).__name__)
    """
    on_line = printed(run(program, at(66 - 7, inner=STRIPE)))
    on_floor = printed(run(program, at(40 - 7, inner=STRIPE)))
    assert on_line == ["5 int 10 int"]
    assert on_floor == ["75 int 10 int"]


def test_color_is_a_color_on_the_floor_and_none_with_nothing_to_see(run, tmp_path):
    """ColorSensor.color() maps COL-COLOR's 1-7 to Color.BLACK ... Color.BROWN and anything else (0, no
    colour) to None (modev3devices.c ev3devices_ColorSensor_color).  A sensor facing forward with no wall
    within reach sees no colour."""
    program = """
        from pybricks.ev3devices import ColorSensor
        from pybricks.parameters import Port, Color
        c = ColorSensor(Port.S3).color()
        print(c, c is None or c in (Color.BLACK, Color.WHITE))
    """
    assert printed(run(program, at(66 - 7, inner=STRIPE))) == ["Color.BLACK True"]
    assert printed(run(program, at(40 - 7, inner=STRIPE))) == ["Color.WHITE True"]
    forward = robot_file(tmp_path, "{port: 3, kind: color, angle_deg: 0, radius_cm: 7, facing: forward}")
    assert printed(run(program, at(100, robot=forward))) == ["None True"]


def test_rgb_scales_the_raw_reading_as_the_firmware(run):
    """ColorSensor.rgb() reads RGB-RAW and scales each component: 0.258 r - 0.3, 0.280 g - 0.8,
    0.523 b - 3.7, truncated to int and kept within 0-100 (modev3devices.c ev3devices_ColorSensor_rgb).
    The raw values come from the same sensor through iodevices.Ev3devSensor (the robot stands still)."""
    result = run(
        """
        from pybricks.ev3devices import ColorSensor
        from pybricks.iodevices import Ev3devSensor
        from pybricks.parameters import Port
        raw = Ev3devSensor(Port.S3).read("RGB-RAW")
        rgb = ColorSensor(Port.S3).rgb()
        print(*raw[:3])
        print(*rgb, type(rgb).__name__)
        """,
        at(40 - 7, inner=STRIPE),
    )
    raw_line, rgb_line = printed(result)
    r, g, b = (int(v) for v in raw_line.split())

    def scale(value):
        return max(0, min(int(value), 100))

    expected = (scale(0.258 * r - 0.3), scale(0.280 * g - 0.8), scale(0.523 * b - 3.7))
    assert rgb_line == " ".join(str(v) for v in expected) + " tuple"
    assert all(0 <= v <= 100 for v in expected) and max(expected) > 50  # white paper reflects


def test_a_mode_is_written_only_when_a_method_needs_another_and_then_costs_the_colour_delay(run):
    """pbdevice.c get_values writes `mode` only when the method's mode differs from the sensor's, and
    then waits get_mode_switch_delay (30 ms for the EV3 colour sensor); otherwise a call is one read of
    bin_data.  So 20 reflection() calls cost far less than 20 alternating reflection()/ambient() calls,
    which pay 20 switches of at least 30 ms."""
    result = run(
        """
        import time
        from pybricks.ev3devices import ColorSensor
        from pybricks.parameters import Port
        sensor = ColorSensor(Port.S3)
        start = time.time()
        for _ in range(20):
            sensor.reflection()
        same = time.time() - start
        start = time.time()
        for _ in range(10):
            sensor.ambient()
            sensor.reflection()
        alternating = time.time() - start
        print(round(same * 1000), round(alternating * 1000))
        """,
        at(40 - 7, inner=STRIPE),
    )
    same_ms, alternating_ms = (int(v) for v in printed(result)[0].split())
    assert same_ms < 20 * 4  # one 2 ms read per call (and the loop's own lines), no mode write
    assert alternating_ms >= 20 * 30 + same_ms  # every call switches: the write, two reads, 30 ms
    samples = [s for s in result.trace.sensor_samples if s]
    assert samples  # (the simulator recorded the measurements the program made)


# --------------------------------------------------------------------------------- UltrasonicSensor


def test_ultrasonic_distance_is_in_mm_and_presence_is_a_bool(run):
    """UltrasonicSensor.distance() reads US-DIST-CM, whose raw value is in tenths of a cm, and returns it
    as an int: mm (modev3devices.c ev3devices_UltrasonicSensor_distance); silent=True reads US-SI-CM, the
    same unit.  presence() is US-LISTEN as a bool (ev3devices_UltrasonicSensor_presence).  The sensor is
    8 cm ahead of the centre at x = 100 cm; the wall's face is at 228 cm."""
    result = run(
        """
        from pybricks.ev3devices import UltrasonicSensor
        from pybricks.parameters import Port
        sonar = UltrasonicSensor(Port.S4)
        print(sonar.distance(), sonar.distance(silent=True), sonar.distance(), sonar.presence())
        """,
        at(100),
    )
    assert printed(result) == ["1200 1200 1200 False"]


def test_silent_distance_measures_anew_on_every_call(run):
    """distance(silent=True) uses the single-measurement mode US-SI-CM, which measures only when the mode
    is written (lego-linux-drivers ev3_uart_sensor_defs.c, LEGO_EV3_ULTRASONIC mode 3); pbdevice.c
    get_values writes it on every call for these modes (`mode >= ..._SI_CM`), so a robot that drives
    towards the wall reads a shorter distance at each call, not the first measurement again."""
    result = run(
        """
        import time
        from pybricks.ev3devices import Motor, UltrasonicSensor
        from pybricks.parameters import Port
        sonar = UltrasonicSensor(Port.S4)
        left, right = Motor(Port.B), Motor(Port.C)
        first = sonar.distance(silent=True)
        left.run(360)
        right.run(360)
        time.sleep(1)
        left.stop()
        right.stop()
        time.sleep(0.3)
        print(first, sonar.distance(silent=True))
        """,
        at(100),
    )
    first, second = (int(v) for v in printed(result)[0].split())
    assert first == 1200
    assert 1200 - second > 100  # one wheel turn is 176 mm; it drove most of one


# -------------------------------------------------------------------------------------- GyroSensor


TURN = """
        import time
        from pybricks.ev3devices import GyroSensor, Motor
        from pybricks.parameters import Direction, Port
        left, right = Motor(Port.B), Motor(Port.C)

        def turn_right(seconds):
            left.run(200)
            right.run(-200)
            time.sleep(seconds)
            left.stop()
            right.stop()
            time.sleep(0.3)
"""


def test_gyro_angle_is_clockwise_positive_and_counterclockwise_negates_it(run):
    """GyroSensor.angle() is GYRO-ANG's raw angle less the offset taken when the object was made (the
    driver counts clockwise positive); with direction=Direction.COUNTERCLOCKWISE it is -raw - offset
    (modev3devices.c ev3devices_GyroSensor_angle, ev3devices_GyroSensor_get_angle_offset, make_new's
    `direction` keyword).  A right turn in the world is a negative heading change."""
    result = run(
        TURN
        + """
        cw = GyroSensor(Port.S2)
        ccw = GyroSensor(Port.S2, direction=Direction.COUNTERCLOCKWISE)
        turn_right(1.5)
        print(cw.angle(), ccw.angle())
        """,
        at(120),
    )
    cw, ccw = (int(v) for v in printed(result)[0].split())
    _, _, heading = result.trace.poses(0)[-1]
    assert cw > 30 and ccw == -cw
    assert abs(cw + heading) <= 2  # the world's heading is counterclockwise positive


def test_gyro_speed_resets_the_angle_as_the_firmware_does(run):
    """speed() reads GYRO-RATE and sets the firmware's offset to 0 ("changing modes resets angle to 0",
    modev3devices.c ev3devices_GyroSensor_speed): the ev3dev gyro resets its angle whenever its mode
    changes (ev3dev/ev3dev#402), so the next angle(), which switches back to GYRO-ANG, reads 0 however the
    robot turned before: the turn before speed() is forgotten.  reset_angle(a)
    (ev3devices_GyroSensor_reset_angle) reads GYRO-ANG and sets the offset so that angle() reads a now,
    without resetting the sensor; later turns add to it."""
    result = run(
        TURN
        + """
        gyro = GyroSensor(Port.S2)
        turn_right(1.0)
        before = gyro.angle()
        left.run(200)
        right.run(-200)
        time.sleep(0.5)
        turning = gyro.speed()
        left.stop()
        right.stop()
        time.sleep(0.3)
        after_speed = gyro.angle()
        gyro.reset_angle(45)
        turn_right(0.5)
        print(before, turning, after_speed, gyro.angle())
        """,
        at(120),
    )
    before, turning, after_speed, final = (int(v) for v in printed(result)[0].split())
    assert before > 30
    assert turning > 30  # deg/s, clockwise positive
    assert after_speed == 0  # the mode switch back to GYRO-ANG reset the sensor, and the offset is 0
    assert final > 45 + 20  # 45 from reset_angle, plus the last turn


def test_gyro_direction_must_be_a_direction(run):
    """make_new takes the direction with pb_type_enum_get_value(direction, &pb_enum_type_Direction): another
    type is a TypeError (modev3devices.c ev3devices_GyroSensor_make_new); the keyword is `direction`, not
    the docs' positive_direction, which the firmware refuses."""
    result = run(
        """
        from pybricks.ev3devices import GyroSensor
        from pybricks.parameters import Direction, Port
        for kwargs in ({"direction": 1}, {"positive_direction": Direction.CLOCKWISE}):
            try:
                GyroSensor(Port.S2, **kwargs)
            except TypeError:
                print("TypeError")
        """,
        at(120),
    )
    assert printed(result) == ["TypeError", "TypeError"]


# ------------------------------------------------------------------------------------- TouchSensor


def test_touch_sensor_is_pressed_only_against_a_wall(run):
    """TouchSensor.pressed() reads TOUCH and is a bool (modev3devices.c ev3devices_TouchSensor_pressed).
    The default robot's bumper is 9 cm ahead of its centre; the wall's face is at 228 cm."""
    program = """
        from pybricks.ev3devices import TouchSensor
        from pybricks.parameters import Port
        print(TouchSensor(Port.S1).pressed())
    """
    assert printed(run(program, at(100))) == ["False"]
    assert printed(run(program, at(218.8))) == ["True"]


# ---------------------------------------------------------------------------------- InfraredSensor


def test_infrared_distance_is_relative_and_the_remote_reads_nothing(run, tmp_path):
    """InfraredSensor.distance() is IR-PROX's 0-100 (modev3devices.c ev3devices_InfraredSensor_distance).
    beacon(channel) reads IR-SEEK and gives (None, None) when the channel's distance is -128 (no beacon);
    buttons(channel) reads IR-REMOTE, 0 meaning no button: []; keypad() reads IR-REM-A, 384 meaning no
    button: [] (ev3devices_InfraredSensor_beacon, _buttons, _keypad).  The simulated world has no remote,
    so those are what the sensor reads.  Each method needs another mode: 1100 ms per switch
    (pbdevice.c get_mode_switch_delay).  A channel outside 1-4 is ValueError (pb_assert INVALID_ARG)."""
    robot = robot_file(tmp_path, "{port: 4, kind: infrared, angle_deg: 0, radius_cm: 8, facing: forward}")
    result = run(
        """
        import time
        from pybricks.ev3devices import InfraredSensor
        from pybricks.parameters import Port
        ir = InfraredSensor(Port.S4)
        start = time.time()
        d = ir.distance()
        print(d, type(d).__name__, round(time.time() - start, 1))
        start = time.time()
        print(ir.beacon(1), ir.buttons(2), ir.keypad(), round(time.time() - start, 1))
        try:
            ir.beacon(5)
        except ValueError:
            print("ValueError")
        """,
        at(228 - 8 - 35, robot=robot),  # the sensor 35 cm from the wall: half of its 70 cm full scale
    )
    first, second, third = printed(result)
    distance, kind, seconds = first.split()
    assert abs(int(distance) - 50) <= 2 and kind == "int" and float(seconds) < 0.1
    assert second == "(None, None) [] [] 3.3"  # three switches of 1.1 s
    assert third == "ValueError"


# ------------------------------------------------------------------------------------------ errors


def test_a_missing_or_other_sensor_is_enodev_and_a_motor_port_is_valueerror(run, tmp_path):
    """pbdevice_get_device raises OSError ENODEV when the port has no sensor of the class's kind (nothing
    there, or another kind: lego_sensor.c ev3_sensor_assert_id), which a program tells by e.args[0] ==
    ENODEV; a sensor class given a motor port is ValueError (get_device: PBIO_ERROR_INVALID_PORT, pb_assert
    -> ValueError)."""
    robot = robot_file(tmp_path, "{port: 3, kind: color, angle_deg: 0, radius_cm: 7, facing: down}")
    result = run(
        """
        from errno import ENODEV
        from pybricks.ev3devices import ColorSensor, GyroSensor, TouchSensor
        from pybricks.parameters import Port
        for make in (lambda: TouchSensor(Port.S1), lambda: GyroSensor(Port.S3)):
            try:
                make()
            except OSError as e:
                if e.args[0] == ENODEV:
                    print("ENODEV")
        try:
            ColorSensor(Port.A)
        except ValueError:
            print("ValueError")
        print(ColorSensor(Port.S3).reflection() > 50)
        """,
        at(40, robot=robot),
    )
    assert printed(result) == ["ENODEV", "ENODEV", "ValueError", "True"]


def test_sensor_readings_are_the_same_in_every_run(run):
    """Runs are deterministic: the same program in the same world prints the same readings."""
    program = (
        TURN
        + """
        from pybricks.ev3devices import ColorSensor, UltrasonicSensor
        gyro, color, sonar = GyroSensor(Port.S2), ColorSensor(Port.S3), UltrasonicSensor(Port.S4)
        turn_right(0.7)
        print(gyro.angle(), gyro.speed(), color.reflection(), color.rgb(), sonar.distance())
    """
    )
    first = printed(run(program, at(100, inner=STRIPE)))
    second = printed(run(program, at(100, inner=STRIPE)))
    assert first == second
