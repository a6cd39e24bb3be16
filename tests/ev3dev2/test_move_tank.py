"""MoveTank and its children: the writes each drive command makes, as python-ev3dev2 2.1.0 makes them."""

import math
import threading
from time import monotonic as real_monotonic
from time import sleep as real_sleep

import pytest

from ev3dev2 import DeviceNotDefined, ThreadNotRunning
from ev3dev2 import motor as motor_module
from ev3dev2.motor import (
    OUTPUT_B,
    OUTPUT_C,
    LineFollowErrorLostLine,
    LineFollowErrorTooFast,
    MoveDifferential,
    MoveJoystick,
    MoveSteering,
    MoveTank,
    SpeedPercent,
    SpeedRPM,
    follow_for_ms,
)
from ev3dev2.sensor.lego import ColorSensor, GyroSensor
from ev3dev2.wheel import EV3Tire

from .fake_brick import sensor, tacho_motor

LEFT, RIGHT = "motor1", "motor2"


def motors(**attrs):
    """Large motors: motor1 on outB (left) and motor2 on outC (right)."""
    return [tacho_motor(LEFT, "outB", **attrs), tacho_motor(RIGHT, "outC", **attrs)]


@pytest.fixture
def tank_brick(make_brick):
    brick = make_brick(motors())
    return brick


def run(brick, move_class, command, *args, **kwargs):
    """Make the drive (logging cleared after construction), run one command, return its writes."""
    drive = move_class(OUTPUT_B, OUTPUT_C, *args)
    brick.clear_log()
    command(drive, **kwargs)
    return brick.writes()


def test_constructing_resets_the_motors_in_port_order(make_brick):
    brick = make_brick(motors())
    MoveTank(OUTPUT_C, OUTPUT_B)

    assert brick.writes() == [(LEFT, "command", "reset"), (RIGHT, "command", "reset")]


def test_on_for_degrees_turns_the_slower_wheel_proportionally_less(tank_brick):
    writes = run(
        tank_brick,
        MoveTank,
        lambda tank: tank.on_for_degrees(SpeedPercent(50), SpeedPercent(25), 360, block=False),
    )

    assert writes == [
        (LEFT, "position_sp", "360"),
        (LEFT, "speed_sp", "525"),
        (LEFT, "stop_action", "hold"),
        (RIGHT, "position_sp", "180"),
        (RIGHT, "speed_sp", "262"),  # 262.5 rounds half to even
        (RIGHT, "stop_action", "hold"),
        (LEFT, "command", "run-to-rel-pos"),
        (RIGHT, "command", "run-to-rel-pos"),
    ]


def test_negative_speed_turns_the_wheel_backwards(tank_brick):
    writes = run(
        tank_brick, MoveTank, lambda tank: tank.on_for_rotations(-30, 30, 1.5, brake=False, block=False)
    )

    assert writes == [
        (LEFT, "position_sp", "-540"),
        (LEFT, "speed_sp", "315"),
        (LEFT, "stop_action", "coast"),
        (RIGHT, "position_sp", "540"),
        (RIGHT, "speed_sp", "315"),
        (RIGHT, "stop_action", "coast"),
        (LEFT, "command", "run-to-rel-pos"),
        (RIGHT, "command", "run-to-rel-pos"),
    ]


def test_on_sets_both_speeds_then_starts_both(tank_brick):
    writes = run(tank_brick, MoveTank, lambda tank: tank.on(-20, SpeedRPM(70)))

    assert writes == [
        (LEFT, "speed_sp", "-210"),
        (RIGHT, "speed_sp", "420"),
        (LEFT, "command", "run-forever"),
        (RIGHT, "command", "run-forever"),
    ]


def test_on_for_seconds(tank_brick):
    writes = run(tank_brick, MoveTank, lambda tank: tank.on_for_seconds(30, 30, 2, block=False))

    assert writes == [
        (LEFT, "speed_sp", "315"),
        (LEFT, "time_sp", "2000"),
        (LEFT, "stop_action", "hold"),
        (RIGHT, "speed_sp", "315"),
        (RIGHT, "time_sp", "2000"),
        (RIGHT, "stop_action", "hold"),
        (LEFT, "command", "run-timed"),
        (RIGHT, "command", "run-timed"),
    ]
    with pytest.raises(ValueError, match=r"^seconds is negative \(-0.5\)$"):
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, -0.5)


def test_off_sets_both_brakes_then_stops_both(tank_brick):
    writes = run(tank_brick, MoveTank, lambda tank: tank.off(brake=False))

    assert writes == [
        (LEFT, "stop_action", "coast"),
        (RIGHT, "stop_action", "coast"),
        (LEFT, "command", "stop"),
        (RIGHT, "command", "stop"),
    ]


def test_blocking_waits_on_each_motor(make_brick):
    brick = make_brick(motors(state=["running", ""]))
    MoveTank(OUTPUT_B, OUTPUT_C).on_for_degrees(50, 50, 90)

    assert [entry for entry in brick.log if entry[0] == "read" and entry[2] == "state"] == [
        ["read", LEFT, "state"],
        ["read", RIGHT, "state"],
        ["read", LEFT, "state"],
        ["read", RIGHT, "state"],
    ]


def test_steering_minus_50_stops_the_left_wheel(tank_brick):
    writes = run(
        tank_brick, MoveSteering, lambda drive: drive.on_for_rotations(-50, SpeedPercent(40), 2, block=False)
    )

    assert writes[:6] == [
        (LEFT, "position_sp", "0"),
        (LEFT, "speed_sp", "0"),
        (LEFT, "stop_action", "hold"),
        (RIGHT, "position_sp", "720"),
        (RIGHT, "speed_sp", "420"),
        (RIGHT, "stop_action", "hold"),
    ]


@pytest.mark.parametrize(
    "steering, left, right",
    [(0, 525, 525), (25, 525, 262), (-25, 262, 525), (100, 525, -525), (-100, -525, 525), (75, 525, -262)],
)
def test_steering_scales_the_inner_wheel(tank_brick, steering, left, right):
    writes = run(tank_brick, MoveSteering, lambda drive: drive.on(steering, 50))

    assert writes[:2] == [(LEFT, "speed_sp", str(left)), (RIGHT, "speed_sp", str(right))]


def test_steering_out_of_range_is_refused(tank_brick):
    with pytest.raises(AssertionError, match="^101 is an invalid steering, must be between -100 and 100"):
        MoveSteering(OUTPUT_B, OUTPUT_C).on(101, 50)


def test_differential_drives_a_distance(tank_brick):
    writes = run(
        tank_brick,
        MoveDifferential,
        lambda drive: drive.on_for_distance(SpeedRPM(40), 500, block=False),
        EV3Tire,
        128,
    )

    degrees = round(500 / (43.2 * math.pi) * 360)
    assert writes[:2] == [(LEFT, "position_sp", str(degrees)), (LEFT, "speed_sp", "240")]
    assert writes[3:5] == [(RIGHT, "position_sp", str(degrees)), (RIGHT, "speed_sp", "240")]


def test_differential_turns_in_place(tank_brick):
    writes = run(
        tank_brick,
        MoveDifferential,
        lambda drive: drive.turn_right(SpeedRPM(40), 90, block=False),
        EV3Tire,
        128,
    )

    # each wheel travels a quarter of the 128 mm circle: 32 pi mm, on a 43.2 mm tire
    degrees = round(32 / 43.2 * 360)
    assert writes[:6] == [
        (LEFT, "position_sp", str(degrees)),
        (LEFT, "speed_sp", "240"),
        (LEFT, "stop_action", "hold"),
        (RIGHT, "position_sp", str(-degrees)),
        (RIGHT, "speed_sp", "240"),
        (RIGHT, "stop_action", "hold"),
    ]


def test_differential_drives_an_arc(tank_brick):
    writes = run(
        tank_brick,
        MoveDifferential,
        lambda drive: drive.on_arc_right(SpeedRPM(80), 150, 700, block=False),
        EV3Tire,
        128,
    )

    # radius 150 mm to the middle: the left wheel is on radius 214, the right on 86
    outer_degrees = 700 * 214 / 150 / (43.2 * math.pi) * 360
    right_speed = 480 * 86 / 214
    assert writes[:2] == [(LEFT, "position_sp", str(round(outer_degrees))), (LEFT, "speed_sp", "480")]
    assert writes[3:5] == [
        (RIGHT, "position_sp", str(round(outer_degrees * 86 / 214))),
        (RIGHT, "speed_sp", str(round(right_speed))),
    ]


def test_differential_refuses_an_arc_tighter_than_the_wheels(tank_brick):
    drive = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3Tire, 128)
    with pytest.raises(
        ValueError, match=r"^MoveDifferential: radius_mm 50 is less than min_circle_radius_mm 64.0$"
    ):
        drive.on_arc_left(30, 50, 100)


def test_odometry_needs_to_be_started(tank_brick):
    drive = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3Tire, 128)
    with pytest.raises(
        ThreadNotRunning, match=r"^odometry_start\(\) must be called to track robot coordinates$"
    ):
        drive.on_to_coordinates(30, 100, 100)
    with pytest.raises(ThreadNotRunning):
        drive.turn_to_angle(30, 90)


def test_odometry_tracks_a_straight_drive(make_brick, monkeypatch):
    # Only the odometry thread reads the positions, so both wheels reach one rotation on its 4th sample.
    make_brick(motors(position=["0", "0", "0", "360"]))
    threads = []

    def start_new_thread(function, args):
        threads.append(threading.Thread(target=function, args=args, daemon=True))
        threads[-1].start()

    monkeypatch.setattr(motor_module._thread, "start_new_thread", start_new_thread)
    drive = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3Tire, 128)
    drive.odometry_start()
    try:
        assert drive.odometry_thread_run
        deadline = real_monotonic() + 5
        while drive.y_pos_mm < 100 and real_monotonic() < deadline:
            real_sleep(0.001)
    finally:
        drive.odometry_stop()
        threads[0].join(5)

    assert drive.y_pos_mm == pytest.approx(43.2 * math.pi)
    assert drive.x_pos_mm == pytest.approx(0, abs=1e-9)
    assert math.degrees(drive.theta) == pytest.approx(90)


@pytest.mark.parametrize(
    "x, y, left, right",
    [(0, 100, 1050, 1050), (100, 0, 1050, -1050), (0, -50, -525, -525), (-100, 0, -1050, 1050)],
)
def test_joystick(tank_brick, x, y, left, right):
    writes = run(tank_brick, MoveJoystick, lambda drive: drive.on(x, y))

    assert writes[:2] == [(LEFT, "speed_sp", str(left)), (RIGHT, "speed_sp", str(right))]


def test_joystick_in_the_middle_stops(tank_brick):
    writes = run(tank_brick, MoveJoystick, lambda drive: drive.on(0, 0))

    assert writes == [
        (LEFT, "stop_action", "hold"),
        (RIGHT, "stop_action", "hold"),
        (LEFT, "command", "stop"),
        (RIGHT, "command", "stop"),
    ]


def test_follow_line_needs_a_color_sensor(tank_brick):
    with pytest.raises(DeviceNotDefined, match="^The 'cs' variable must be defined with a ColorSensor"):
        MoveTank(OUTPUT_B, OUTPUT_C).follow_line(1, 0, 0, 30)


def test_follow_line_stops_when_it_loses_the_line(make_brick):
    brick = make_brick(
        motors(), sensor("sensor0", "in1", "lego-ev3-color", value0=["30", "20", "80", "80", "80"])
    )
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.cs = ColorSensor()
    brick.clear_log()

    with pytest.raises(LineFollowErrorLostLine, match="^we lost the line$"):
        tank.follow_line(kp=2, ki=0, kd=0, speed=SpeedPercent(20), white=60, off_line_count_max=3)

    speeds = [write for write in brick.writes() if write[1] == "speed_sp"]
    # target 30: reading 20 turns left (error 10 * kp 2), then 80 turns right hard
    assert speeds == [
        (LEFT, "speed_sp", "190"),
        (RIGHT, "speed_sp", "230"),
        (LEFT, "speed_sp", "310"),
        (RIGHT, "speed_sp", "110"),
        (LEFT, "speed_sp", "310"),
        (RIGHT, "speed_sp", "110"),
    ]
    assert brick.writes()[-2:] == [(LEFT, "command", "stop"), (RIGHT, "command", "stop")]


def test_follow_line_for_some_milliseconds(make_brick):
    brick = make_brick(motors(), sensor("sensor0", "in1", "lego-ev3-color", value0="30"))
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.cs = ColorSensor()
    start = brick.clock

    tank.follow_line(kp=1, ki=0, kd=0, speed=20, sleep_time=0.01, follow_for=follow_for_ms, ms=100)

    assert brick.clock - start == pytest.approx(0.1, abs=0.011)
    assert brick.writes()[-2:] == [(LEFT, "command", "stop"), (RIGHT, "command", "stop")]
    assert tank.stopwatch is None


def test_follow_line_too_fast(make_brick):
    make_brick(motors(), sensor("sensor0", "in1", "lego-ev3-color", value0=["50", "0"]))
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.cs = ColorSensor()

    with pytest.raises(LineFollowErrorTooFast, match="^The robot is moving too fast to follow the line$"):
        tank.follow_line(kp=100, ki=0, kd=0, speed=SpeedPercent(90))


def test_turn_degrees_with_the_gyro_until_within_the_margin(make_brick):
    gyro_angles = ["0", "0", "0", "10", "25", "29"]
    brick = make_brick(motors(), sensor("sensor0", "in2", "lego-ev3-gyro", value0=gyro_angles))
    tank = MoveTank(OUTPUT_B, OUTPUT_C)
    tank.gyro = GyroSensor()
    brick.clear_log()

    tank.turn_right(SpeedPercent(10), 30)

    assert brick.writes() == [
        (LEFT, "speed_sp", "105"),
        (RIGHT, "speed_sp", "-105"),
        (LEFT, "command", "run-forever"),
        (RIGHT, "command", "run-forever"),
    ] * 3 + [
        (LEFT, "stop_action", "hold"),
        (RIGHT, "stop_action", "hold"),
        (LEFT, "command", "stop"),
        (RIGHT, "command", "stop"),
    ]


def test_turn_degrees_needs_a_gyro(tank_brick):
    with pytest.raises(DeviceNotDefined, match="^The 'gyro' variable must be defined with a GyroSensor"):
        MoveTank(OUTPUT_B, OUTPUT_C).turn_left(10, 90)
