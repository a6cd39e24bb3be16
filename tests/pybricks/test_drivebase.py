"""pybricks.robotics.DriveBase behaves as on an EV3 with Pybricks 2.0 (pybricks-micropython v2.0.0).

Sources: extmod/modrobotics.c (DriveBase methods, settings defaults = limits / 3, wait_for_completion),
lib/pbio/src/drivebase.c (setup, claims, straight / turn / drive), lib/pbio/src/trajectory.c (the
profile, here in tests/pybricks/firmware_trajectory.py), bricks/ev3dev/modules/pybricks/robotics.py
(1.0's stop(Stop.X) and drive_time).  Runs are deterministic: the robot starts at (60 cm, 120 cm),
heading 0 (east), in an empty walled arena; 10 ms ticks.
"""

import math

import pytest

from tests.pybricks import firmware_trajectory as fw
from tests.pybricks.printed import TIMED, output

TICK = 0.01
HEADER = (
    TIMED
    + """
from pybricks.ev3devices import Motor
from pybricks.parameters import Port, Stop, Direction
from pybricks.robotics import DriveBase
left, right = Motor(Port.B), Motor(Port.C)
db = DriveBase(left, right, 56, 120)
"""
)


def pose(result):
    return result.trace.poses(0)[-1]


def motion_seconds(result) -> float:
    """How long the robot moved: from the first tick its pose changed to the last (10 ms ticks)."""
    poses = result.trace.poses(0)
    moving = [i for i in range(1, len(poses)) if abs(poses[i] - poses[i - 1]).max() > 1e-6]
    return (moving[-1] - moving[0] + 1) * TICK


# The shim's own sysfs writes and reads (3 ms and 2 ms of simulated time each, as python-ev3dev2's
# cost on a brick) come before and after the move: a blocking call returns this much later at most.
IO_S = 0.05
# The simulated motor's ramp down lands exactly on the target, tick by tick; at a low acceleration it
# gets there up to three ticks before the firmware's profile would (a known difference).
PROFILE_S = 3 * TICK


def test_settings_defaults_are_a_third_of_the_limits(run):
    """modrobotics.c robotics_DriveBase_make_new: straight_speed etc. are the distance and heading
    controllers' limits / 3, in mm and degrees; drivebase.c drivebase_adopt_settings sums the motors'
    max rates and doubles their summed accelerations; the scales are pbio_drivebase_setup's."""
    result = run(HEADER + "print('settings', *db.settings())\n")
    assert [int(v) for v in output(result)["settings"]] == list(fw.drive_base_defaults(56, 120))
    assert fw.drive_base_defaults(56, 120) == (130, 521, 124, 497)


@pytest.mark.parametrize(
    "distance, settings",
    [
        (500, None),  # a long move: accelerate, cruise, decelerate
        (20, None),  # a short one: a triangle
        (-300, None),  # backwards
        (400, (250, 200, 90, 180)),  # custom settings()
    ],
)
def test_straight_lands_where_and_when_the_firmware_trapezoid_does(run, distance, settings):
    """drivebase.c pbio_drivebase_straight: the sum of the counts follows
    pbio_trajectory_make_angle_based (trajectory.c) at settings()' speed and acceleration, while the
    heading holds; straight blocks until done (modrobotics.c wait_for_completion_drivebase) and
    leaves the base holding."""
    set_line = f"db.settings(*{settings})\n" if settings else ""
    result = run(
        HEADER + set_line + f"timed('straight', lambda: db.straight({distance}))\nprint('d', db.distance())\n"
    )
    out = output(result)
    speed, accel = (settings or fw.drive_base_defaults(56, 120))[:2]
    ref = fw.straight(distance, speed, accel)
    wheel_deg = ref.th3 / 4  # each wheel turns half the sum, 2 counts per degree
    expected_mm = wheel_deg / 360 * math.pi * 56
    x, y, heading = pose(result)
    assert abs((x - 60) * 10 - expected_mm) <= 1.0
    assert abs(expected_mm - distance) <= 1.0
    assert abs(y - 120) < 0.1 and abs(heading) < 0.2
    assert abs(motion_seconds(result) - ref.t3_us / 1e6) <= PROFILE_S
    assert ref.t3_us / 1e6 - TICK <= float(out["straight"][0]) <= ref.t3_us / 1e6 + IO_S
    assert int(out["d"][0]) == distance


@pytest.mark.parametrize(
    "angle, settings", [(90, None), (-45, None), (10, None), (180, (100, 300, 200, 300))]
)
def test_turn_is_clockwise_positive_and_follows_the_firmware_trapezoid(run, angle, settings):
    """drivebase.c pbio_drivebase_turn: the difference left - right follows the trapezoid, so a positive
    angle turns the robot to the right (clockwise, seen from above); the distance holds."""
    set_line = f"db.settings(*{settings})\n" if settings else ""
    result = run(HEADER + set_line + f"timed('turn', lambda: db.turn({angle}))\nprint('a', db.angle())\n")
    out = output(result)
    rate, accel = (settings or fw.drive_base_defaults(56, 120))[2:]
    ref = fw.turn(angle, rate, accel)
    wheel_deg = ref.th3 / 4
    robot_deg = wheel_deg * 56 / 120
    x, y, heading = pose(result)
    assert abs(heading + robot_deg) <= 1.0  # the trace's heading is counterclockwise-positive
    assert abs(robot_deg - angle) <= 1.0
    assert abs(x - 60) < 0.2 and abs(y - 120) < 0.2
    assert abs(motion_seconds(result) - ref.t3_us / 1e6) <= PROFILE_S
    assert ref.t3_us / 1e6 - TICK <= float(out["turn"][0]) <= ref.t3_us / 1e6 + IO_S
    assert int(out["a"][0]) == angle


def test_motors_are_claimed_while_the_drive_base_is_active(run):
    """drivebase.c pbio_drivebase_claim_servos: straight, turn and drive claim the motors, and only
    a stop (coast or brake actuation) lets them go; servo.c refuses run, dc, stop and reset_angle on a
    claimed servo with PBIO_ERROR_INVALID_OP, which pb_assert raises as OSError EPERM.  settings()
    raises it while either controller is active (modrobotics.c robotics_DriveBase_settings), which
    is also while it holds after a straight."""
    result = run(
        HEADER
        + """
def attempt(label, call):
    try:
        call()
        print(label, 'ok')
    except OSError as error:
        print(label, error.errno)

attempt('settings-new', lambda: db.settings(100))
db.straight(100)
attempt('run', lambda: left.run(100))
attempt('dc', lambda: right.dc(50))
attempt('reset_angle', lambda: left.reset_angle(0))
attempt('settings-holding', lambda: db.settings(100))
print('read', *db.settings())
db.drive(100, 0)
attempt('settings-driving', lambda: db.settings(100))
db.stop()
attempt('settings-stopped', lambda: db.settings(150))
attempt('run-stopped', lambda: left.run(100))
left.stop()
"""
    )
    out = output(result)
    assert out["settings-new"] == ["ok"]
    for label in ("run", "dc", "reset_angle", "settings-holding", "settings-driving"):
        assert out[label] == ["1"], label  # EPERM
    assert out["settings-stopped"] == ["ok"] and out["run-stopped"] == ["ok"]


def test_drive_returns_at_once_and_its_speed_is_clamped_at_the_limit(run):
    """modrobotics.c robotics_DriveBase_drive returns at once; drivebase.c pbio_drivebase_drive starts
    timed control with the controllers' max_rate as limit (trajectory.c make_time_based clamps the
    target speed to wmax): 2 x 1600 counts/s of the sum, 391 mm/s with 56 mm wheels."""
    result = run(
        HEADER
        + """
timed('drive', lambda: db.drive(1000, 0))
time.sleep(1.5)
print('state', *db.state())
db.stop()
"""
    )
    out = output(result)
    assert float(out["drive"][0]) <= IO_S
    per_mm, _ = fw.drive_base_scales(56, 120)
    limit = fw.to_user(2 * 1600, per_mm)
    assert limit == 391
    distance, speed, angle, turn_rate = (int(v) for v in out["state"])
    assert abs(speed - limit) <= 2 and abs(turn_rate) <= 2
    assert abs(angle) <= 2  # (the two wheels' counts are read 2 ms apart, at 800 deg/s)
    assert abs(pose(result)[2]) < 0.5


def test_compatibility_stop_modes_and_drive_time(run):
    """bricks/ev3dev/modules/pybricks/robotics.py: DriveBase.stop(Stop.BRAKE) stops and brakes both
    motors, stop(Stop.HOLD) is straight(0) (so the motors stay claimed and held), and
    drive_time(speed, steering, time) is drive, wait(time), stop."""
    result = run(
        HEADER
        + """
timed('drive_time', lambda: db.drive_time(100, 0, 1000))
print('after', left.speed() > 0)
db.drive(100, 0)
time.sleep(0.5)
db.stop(Stop.BRAKE)
time.sleep(0.1)
print('brake', left.speed(), left.control.done())
db.drive(100, 0)
time.sleep(0.5)
db.stop(Stop.HOLD)
try:
    left.run(10)
except OSError as error:
    print('hold-claimed', error.errno)
db.stop()
"""
    )
    out = output(result)
    assert 1.0 <= float(out["drive_time"][0]) <= 1.0 + IO_S
    assert out["brake"] == ["0", "True"]
    assert out["hold-claimed"] == ["1"]


def test_reversed_motors_drive_backwards(run):
    """modmotor.c motor_Motor_make_new: positive_direction=Direction.COUNTERCLOCKWISE negates the
    motor's angle, speed and commands (tacho.c pbio_tacho_get_count), so a base made of two such
    motors drives backwards when told to go forward."""
    source = HEADER.replace(
        "Motor(Port.B), Motor(Port.C)",
        "Motor(Port.B, Direction.COUNTERCLOCKWISE), Motor(Port.C, Direction.COUNTERCLOCKWISE)",
    )
    result = run(source + "db.straight(200)\nprint('d', db.distance(), left.angle())\n")
    out = output(result)
    x, _, _ = pose(result)
    assert abs((x - 60) * 10 + 200) <= 1.0
    assert out["d"][0] == "200" and int(out["d"][1]) > 0


def test_a_robot_file_gives_the_wheels_as_drivebase_takes_them(run):
    """A robot file says wheel_diameter_mm and axle_track_mm, the figures LEGO's building instructions and
    DriveBase(left, right, wheel_diameter, axle_track) use (pybricks-api robotics.DriveBase): a program
    giving its robot's figures drives the distances and turns the angles it asks for, with small wheels
    as with the set's own."""
    from ev3sim2d.world.robot_spec import parse_robot

    spec = parse_robot(
        "name: small wheels\nwheel_diameter_mm: 43.2\naxle_track_mm: 100\n"
        "body: {front_cm: 8, back_cm: 6, width_cm: 13}\n"
        "motors:\n  - {port: outB, kind: large, wheel: left}\n  - {port: outC, kind: large, wheel: right}\n"
    )
    result = run(
        HEADER
        + """
robot = DriveBase(Motor(Port.B), Motor(Port.C), wheel_diameter=43.2, axle_track=100)
robot.straight(300)
robot.turn(90)
print('done', robot.distance(), robot.angle())
""",
        robot=spec,
    )
    out = output(result)
    assert out["done"] == ["300", "90"]
    x, y, heading = pose(result)
    start = result.trace.poses(0)[0]
    assert math.isclose(math.hypot(x - start[0], y - start[1]), 30, abs_tol=0.1)
    assert math.isclose((start[2] - heading) % 360, 90, abs_tol=1)  # clockwise: the world's angle falls
