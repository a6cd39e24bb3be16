"""Where and when a Pybricks 2.0 move ends on a brick: the firmware's trapezoid, for the tests.

Written from pybricks-micropython v2.0.0, lib/pbio/src/trajectory.c (pbio_trajectory_make_angle_based,
pbio_trajectory_make_time_based, with the timest / wdiva macros of trajectory.h), the unit conversions
of lib/pbio/src/math.c and control.c (pbio_control_user_to_counts), and drivebase.c
(pbio_drivebase_setup: counts per mm and per degree of a drive base).  Integer arithmetic as in C
(division truncates toward zero); times in microseconds, angles in encoder counts (2 per degree on
ev3dev_stretch), speeds in counts/s.  Independent of the shim's own code on purpose.
"""

from dataclasses import dataclass

ONE = 1 << 16  # fix16 1.0
FOUR_DIV_PI = 0x145F3  # libfixmath


def c_div(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def mul_fix16(a: int, b: int) -> int:
    """fix16_mul and pbio_math_mul_i32_fix16: the product, rounded (half up; -1/2 down)."""
    p = a * b
    if p < 0:
        p -= 1
    return (p >> 16) + ((p & 0x8000) >> 15)


def div_fix16(a: int, b: int) -> int:
    """fix16_div, rounded to the nearest."""
    q = (2 * abs(a) * ONE + abs(b)) // (2 * abs(b))
    return q if (a < 0) == (b < 0) else -q


def to_counts(user: int, counts_per_unit: int) -> int:
    return mul_fix16(user, counts_per_unit)


def to_user(counts: int, counts_per_unit: int) -> int:
    return counts if counts_per_unit == ONE else mul_fix16(counts, div_fix16(ONE, counts_per_unit))


def timest(b, t):
    return c_div(b * c_div(t, 1000), 1000)


def x_time(b, t):
    return c_div(b * t, 1000)


def x_time2(b, t):
    return c_div(x_time(x_time(b, t), t), 2000)


def wdiva(w, a):
    return c_div(w * 1000, a) * 1000


def firmware_sqrt(n: int) -> int:
    return 0 if n <= 0 else _newton(n)


def _newton(n):
    x0 = n
    while True:
        x1 = (x0 + n // x0) // 2
        if x1 in (x0, x0 + 1):
            return x0
        x0 = x1


@dataclass
class Trajectory:
    t3_us: int  # when the move ends
    th3: int  # where it ends (counts)
    w1: int  # the cruise (or peak) speed, counts/s
    t1_us: int
    t2_us: int


def angle_based(th0: int, th3: int, wt: int, wmax: int, a: int, w0: int = 0) -> Trajectory:
    """pbio_trajectory_make_angle_based from standstill (w0 = 0) unless told, t0 = 0."""
    if th3 == th0:
        return Trajectory(0, th0, 0, 0, 0)
    backward = th3 < th0
    if backward:
        th3, w0 = 2 * th0 - th3, -w0
    wt = min(abs(wt), wmax)
    if w0 < wt:
        a0 = a
        thf = th0 - c_div(w0 * w0, 2 * a)
        if th3 - thf >= c_div(wt * wt, a):
            th1, th2, w1 = thf + c_div(wt * wt, 2 * a), th3 - c_div(wt * wt, 2 * a), wt
        else:
            th1 = c_div(th3 + thf, 2)
            th2, w1 = th1, firmware_sqrt(2 * a * (th1 - thf))
    else:
        a0 = -a
        th1, th2, w1 = th0 + c_div(w0 * w0 - wt * wt, 2 * a), th3 - c_div(wt * wt, 2 * a), wt
    t1 = wdiva(w1 - w0, a0)
    t2 = t1 + (0 if th2 == th1 else wdiva(th2 - th1, w1))
    t3 = t2 + wdiva(w1, a)
    if backward:
        th3, w1 = 2 * th0 - th3, -w1
    return Trajectory(t3, th3, w1, t1, t2)


def time_based(duration_us: int, wt: int, wmax: int, a: int) -> Trajectory:
    """pbio_trajectory_make_time_based from standstill, t0 = 0, th0 = 0: (th3 is the counts turned)."""
    sign = -1 if wt < 0 else 1
    wt = abs(wt)
    top = min(wmax, timest(a, duration_us))
    wt = min(wt, top)
    if wdiva(wt, a) - c_div(duration_us, 2) < 0:
        t1, w1 = wdiva(wt, a), wt
    else:
        t1, w1 = c_div(duration_us, 2), c_div(timest(a, duration_us), 2)
    t3mt2 = wdiva(w1, a)
    t2 = duration_us - t3mt2
    mth1 = x_time2(a, t1)
    mth2 = mth1 + x_time(w1, t2 - t1)
    mth3 = mth2 + x_time(w1, t3mt2) + x_time2(-a, t3mt2)
    th3 = c_div(mth3, 1000)
    return Trajectory(duration_us, sign * th3, sign * w1, t1, t2)


# ------------------------------------------------------------------ motors and drive bases
LARGE = {"max_rate": 1600, "acceleration": 3200}  # servo.c settings_servo_ev3_large (counts)
MEDIUM = {"max_rate": 2000, "acceleration": 8000}  # settings_servo_ev3_medium
MOTOR_COUNTS_PER_DEGREE = 2 * ONE


def fix16(value) -> int:
    return int(value * ONE + 0.5) if isinstance(value, float) else value * ONE


def drive_base_scales(wheel_diameter, axle_track) -> tuple[int, int]:
    """(counts of the two motors' sum per mm, counts of their difference per degree), fix16
    (drivebase.c pbio_drivebase_setup)."""
    d, t = fix16(wheel_diameter), fix16(axle_track)
    per_mm = mul_fix16(MOTOR_COUNTS_PER_DEGREE, div_fix16(mul_fix16(180 * ONE, FOUR_DIV_PI), d))
    per_deg = mul_fix16(MOTOR_COUNTS_PER_DEGREE, div_fix16(mul_fix16(t, 2 * ONE), d))
    return per_mm, per_deg


def drive_base_defaults(wheel_diameter, axle_track, motor=LARGE) -> tuple[int, int, int, int]:
    """DriveBase.settings() as made (modrobotics.c: the limits / 3; drivebase_adopt_settings: sum of
    the two motors' max rates, twice the sum of their accelerations)."""
    per_mm, per_deg = drive_base_scales(wheel_diameter, axle_track)
    rate, accel = 2 * motor["max_rate"], 2 * 2 * motor["acceleration"]
    return (
        to_user(rate, per_mm) // 3,
        to_user(accel, per_mm) // 3,
        to_user(rate, per_deg) // 3,
        to_user(accel, per_deg) // 3,
    )


def straight(distance_mm, speed, acceleration, wheel_diameter=56, axle_track=120, motor=LARGE) -> Trajectory:
    """A DriveBase.straight: the sum controller's trajectory (th3 in sum counts: each wheel turns
    th3 / 4 degrees)."""
    per_mm, _ = drive_base_scales(wheel_diameter, axle_track)
    wmax = 2 * motor["max_rate"]
    rel, rate, acc = (to_counts(v, per_mm) for v in (distance_mm, speed, acceleration))
    return angle_based(0, rel, rate, wmax, min(acc, 4 * motor["acceleration"]))


def turn(angle_deg, rate, acceleration, wheel_diameter=56, axle_track=120, motor=LARGE) -> Trajectory:
    """A DriveBase.turn: the difference controller's trajectory (each wheel turns th3 / 4 degrees)."""
    _, per_deg = drive_base_scales(wheel_diameter, axle_track)
    wmax = 2 * motor["max_rate"]
    rel, w, acc = (to_counts(v, per_deg) for v in (angle_deg, rate, acceleration))
    return angle_based(0, rel, w, wmax, min(acc, 4 * motor["acceleration"]))


def run_angle(speed, angle, motor=LARGE, max_speed=None, acceleration=None) -> Trajectory:
    """A Motor.run_angle / run_target from standstill at angle 0 (a negative speed flips the angle)."""
    rel = 2 * angle * (-1 if speed < 0 else 1)
    wmax = 2 * max_speed if max_speed else motor["max_rate"]
    a = 2 * acceleration if acceleration else motor["acceleration"]
    return angle_based(0, rel, 2 * speed, wmax, a)
