"""pybricks.ev3devices.Motor behaves as on an EV3 with Pybricks 2.0 (pybricks-micropython v2.0.0).

Sources: extmod/modmotor.c (the methods, their arguments and waiting), extmod/modbuiltins.c (Control),
lib/pbio/src/servo.c (settings per motor type, in counts: 2 per degree on ev3dev_stretch), control.c
(relative moves, limits), trajectory.c (the profile: tests/pybricks/firmware_trajectory.py),
bricks/ev3dev/modules/pybricks/ev3devices.py (EV3 MicroPython 1.0's methods).  The default robot has
Large motors on B and C (the wheels) and a Medium motor on A that drives nothing.
"""

from tests.pybricks import firmware_trajectory as fw
from tests.pybricks.printed import TIMED, output

TICK = 0.01
IO_S = 0.05  # the shim's sysfs writes and reads before and after a move (3 ms and 2 ms each)
HEADER = (
    TIMED
    + """
from pybricks.ev3devices import Motor
from pybricks.parameters import Port, Stop, Direction
"""
)


def test_limits_and_defaults_per_motor_type(run):
    """servo.c settings_servo_ev3_large / _medium in counts (2 per degree): Large 800 deg/s and
    1600 deg/s/s, Medium 1000 and 4000, read through control.limits() (control.c
    pbio_control_settings_get_limits); control.scale is counts per degree (modbuiltins.c)."""
    result = run(
        HEADER
        + """
print('large', *Motor(Port.B).control.limits(), Motor(Port.B).control.scale)
print('medium', *Motor(Port.A).control.limits(), *Motor(Port.A).control.pid())
print('geared', *Motor(Port.A, gears=[12, 36]).control.limits(), Motor(Port.A, gears=[[12, 36], [1, 2]]).control.scale)
"""
    )
    out = output(result)
    assert out["large"] == ["800", "1600", "100", "2.0"]
    assert out["medium"][:3] == ["1000", "4000", "100"] and out["medium"][-1] == "20"
    cpu = fw.mul_fix16(2 * fw.ONE, 3 * fw.ONE)
    assert out["geared"][:2] == [str(fw.to_user(2000, cpu)), str(fw.to_user(8000, cpu))]
    assert out["geared"][-1] == "12.0"


def test_run_angle_and_run_target_follow_the_firmware_trapezoid(run):
    """control.c pbio_control_start_relative_angle_control and trajectory.c
    pbio_trajectory_make_angle_based: the move lands on its target and takes t3; a negative speed
    reverses run_angle (both negative is forward); run_target ignores the speed's sign; both block and
    hold by default (modmotor.c motor_Motor_run_angle / _run_target)."""
    cases = [
        ("long", "B", 500, 720, {}),
        ("short", "B", 800, 30, {}),  # a triangle
        ("negative", "B", -400, 180, {}),
        ("both-negative", "B", -400, -180, {}),
        ("medium", "A", 900, 540, {"motor": fw.MEDIUM}),
        ("custom", "A", 600, 360, {"motor": fw.MEDIUM, "max_speed": 300, "acceleration": 500}),
    ]
    lines = ["m = {'A': Motor(Port.A), 'B': Motor(Port.B)}", "m['A'].control.limits(1000, 4000)"]
    for label, port, speed, angle, extra in cases:
        if "max_speed" in extra:
            lines.append(f"m['{port}'].stop()")  # (limits cannot change while it holds)
            lines.append(f"m['{port}'].control.limits({extra['max_speed']}, {extra['acceleration']})")
        lines.append(f"m['{port}'].reset_angle(0)")
        lines.append(f"timed('{label}', lambda: m['{port}'].run_angle({speed}, {angle}))")
        lines.append(f"print('{label}-angle', m['{port}'].angle())")
    lines.append("m['B'].reset_angle(0)")
    lines.append("timed('target', lambda: m['B'].run_target(-500, 270))")
    lines.append("print('target-angle', m['B'].angle())")
    result = run(HEADER + "\n".join(lines) + "\n", time_limit_s=60)
    out = output(result)
    for label, _, speed, angle, extra in cases:
        ref = fw.run_angle(speed, angle, **extra)
        assert int(out[f"{label}-angle"][0]) == ref.th3 // 2, label
        assert abs(float(out[label][0]) - ref.t3_us / 1e6) <= 2 * TICK + IO_S, (label, out[label], ref)
    assert out["both-negative-angle"] == ["180"] and out["negative-angle"] == ["-180"]
    assert out["target-angle"] == ["270"]
    ref = fw.run_angle(500, 270)
    assert abs(float(out["target"][0]) - ref.t3_us / 1e6) <= 2 * TICK + IO_S


def test_run_time_takes_its_time_and_floats_are_truncated(run):
    """trajectory.c pbio_trajectory_make_time_based: run_time accelerates, cruises and slows down to
    stand still at `time` ms; modmotor.c reads arguments with pb_obj_get_int, so 0.5 ms is 0 ms and
    90.9 degrees is 90."""
    result = run(
        HEADER
        + """
m = Motor(Port.A)
timed('run_time', lambda: m.run_time(1000, 2000))
print('turned', m.angle())
timed('half', lambda: m.run_time(500, 0.5))
m.reset_angle(0)
m.run_angle(500.9, 90.9)
print('float', m.angle())
"""
    )
    out = output(result)
    assert 2.0 <= float(out["run_time"][0]) <= 2.0 + IO_S
    ref = fw.time_based(2_000_000, 2000, 2000, 8000)
    assert abs(int(out["turned"][0]) - ref.th3 // 2) <= 2
    assert float(out["half"][0]) <= IO_S
    assert out["float"] == ["90"]


def test_speed_zero_and_nonblocking_moves(run):
    """trajectory.c pbio_trajectory_make_angle_based returns PBIO_ERROR_INVALID_ARG for speed 0
    (ValueError), but control.c starts a hold for a relative move of 0 before looking at the speed;
    run, dc and track_target return at once, and a move with wait=False still ends and holds."""
    result = run(
        HEADER
        + """
m = Motor(Port.A)
for label, call in [('angle0', lambda: m.run_angle(0, 90)), ('zero-zero', lambda: m.run_angle(0, 0)),
                    ('target0', lambda: m.run_target(0, 90))]:
    try:
        call()
        print(label, 'ok')
    except ValueError:
        print(label, 'ValueError')
timed('run', lambda: m.run(500))
timed('dc', lambda: m.dc(50))
m.stop()
time.sleep(0.5)
m.reset_angle(0)
timed('nowait', lambda: m.run_angle(500, 360, wait=False))
print('done-early', m.control.done())
time.sleep(1.5)
print('done-late', m.control.done(), m.angle())
timed('track', lambda: m.track_target(450))
time.sleep(0.5)
print('tracked', m.angle())
"""
    )
    out = output(result)
    assert out["angle0"] == ["ValueError"] and out["target0"] == ["ValueError"]
    assert out["zero-zero"] == ["ok"]
    assert float(out["run"][0]) <= IO_S and float(out["dc"][0]) <= IO_S
    assert float(out["nowait"][0]) <= IO_S
    assert out["done-early"] == ["False"] and out["done-late"] == ["True", "360"]
    assert float(out["track"][0]) <= IO_S and out["tracked"] == ["450"]


def test_stop_modes(run):
    """modmotor.c: stop() coasts, brake() brakes, hold() holds (servo.c pbio_servo_stop); 1.0's
    stop(Stop.X) picks one of them (bricks/ev3dev/modules/pybricks/ev3devices.py Motor.stop)."""
    result = run(
        HEADER
        + """
m = Motor(Port.A)
for label, stop in [('coast', m.stop), ('brake', m.brake), ('hold', m.hold), ('compat-brake', lambda: m.stop(Stop.BRAKE))]:
    m.run(800)
    time.sleep(1)
    stop()
    time.sleep(0.02)
    print(label, m.speed(), m.control.done())
    time.sleep(0.5)
"""
    )
    out = output(result)
    assert int(out["coast"][0]) > 100  # still rolling out
    assert out["brake"][0] == "0" and out["hold"][0] == "0" and out["compat-brake"][0] == "0"


def test_errors_for_wrong_ports_and_missing_motors(run):
    """_device.find: a sensor port is ValueError (PBIO_ERROR_INVALID_PORT), no motor there is OSError
    ENODEV (pbio_servo_setup / pb_assert); reset_angle() without an angle needs an absolute count,
    which ev3dev's counter lacks: OSError EOPNOTSUPP (servo.c pbio_servo_reset_angle, counter_core.c)."""
    result = run(
        HEADER
        + """
import errno
for label, call in [('sensor-port', lambda: Motor(Port.S1)), ('missing', lambda: Motor(Port.D)),
                    ('reset-abs', lambda: Motor(Port.A).reset_angle())]:
    try:
        call()
        print(label, 'ok')
    except ValueError:
        print(label, 'ValueError')
    except OSError as error:
        print(label, 'EOPNOTSUPP' if error.errno == errno.EOPNOTSUPP else errno.errorcode[error.errno])
"""
    )
    out = output(result)
    assert out == {"sensor-port": ["ValueError"], "missing": ["ENODEV"], "reset-abs": ["EOPNOTSUPP"]}


def test_compatibility_settings_and_busy_control(run):
    """ev3devices.py (1.0): set_run_settings is control.limits; modbuiltins.c raise_if_control_busy:
    settings cannot change while the motor holds after a move (OSError EPERM) until it stops."""
    result = run(
        HEADER
        + """
m = Motor(Port.A)
m.set_run_settings(500, 1000)
print('limits', *m.control.limits())
m.run_angle(300, 90)
try:
    m.set_run_settings(400, 1000)
except OSError as error:
    print('busy', error.errno)
m.stop()
m.set_run_settings(400, 1000)
print('stalled', m.stalled())
"""
    )
    out = output(result)
    assert out["limits"] == ["500", "1000", "100"]
    assert out["busy"] == ["1"] and out["stalled"] == ["False"]


def test_a_dc_motor_runs_by_duty_cycle_only_and_is_found_like_a_motor(run):
    """extmod/modmotor.c motor_DCMotor_type (listed by modiodevices.c for the EV3): dc(duty) drives the
    motor without speed control, stop() coasts and brake() shorts it (pbio_dcmotor_coast / _brake);
    nothing on the port is ENODEV, a sensor port ValueError."""
    result = run(
        HEADER
        + """
from errno import ENODEV
from pybricks.iodevices import DCMotor
motor, counter = DCMotor(Port.B), Motor(Port.B)
motor.dc(50)
time.sleep(1)
print('ran', counter.angle())
motor.brake()
time.sleep(0.5)
print('braked', counter.angle())
time.sleep(0.5)
print('still', counter.angle())
counter_c = Motor(Port.C)  # (a Motor counts from 0 where it is made)
backwards = DCMotor(Port.C, Direction.COUNTERCLOCKWISE)
backwards.dc(20)
time.sleep(1)
backwards.stop()
print('backwards', counter_c.angle() < -150)
try:
    DCMotor(Port.D)
except OSError as e:
    print('missing', e.args[0] == ENODEV)
try:
    DCMotor(Port.S1)
except ValueError:
    print('sensor-port', True)
"""
    )
    out = output(result)
    ran = int(out["ran"][0])
    assert abs(ran - 0.5 * 1050) < 0.03 * 525  # half of the driver's max_speed for about a second
    braked = int(out["braked"][0])
    assert 0 <= braked - ran < 15 and out["still"] == [str(braked)]  # stopped within the brake's writes
    assert out["backwards"] == out["missing"] == out["sensor-port"] == ["True"]


def test_run_until_stalled_blocks_until_the_end_stop_and_returns_the_angle_there(run):
    """modmotor.c motor_Motor_run_until_stalled: it always waits, until the motor stalls (an arm against
    its end stop, here 90 degrees away), then stops with `then` (COAST by default) and returns the angle;
    both directions."""
    from ev3sim2d.world.robot_spec import parse_robot

    spec = parse_robot(
        "name: arm\nwheel_diameter_mm: 56\naxle_track_mm: 120\nbody: {front_cm: 9, back_cm: 7, width_cm: 15}\n"
        "motors:\n  - {port: B, kind: large, wheel: left}\n  - {port: C, kind: large, wheel: right}\n"
        "  - {port: A, kind: medium, limits_deg: [-30, 90]}\n"
    )
    result = run(
        HEADER
        + """
arm = Motor(Port.A)
start = time.time()
print('up', arm.run_until_stalled(300), round(time.time() - start, 2))
print('down', arm.run_until_stalled(-300, then=Stop.HOLD))
time.sleep(0.5)
print('held', arm.angle())
""",
        robot=spec,
    )
    out = output(result)
    assert abs(int(out["up"][0]) - 90) <= 1
    assert 0.3 <= float(out["up"][1]) <= 0.8  # 90 degrees at 300 deg/s after the ramp, then the stall time
    assert abs(int(out["down"][0]) + 30) <= 1 and out["held"] == out["down"][:1]
