"""Motor: speed units, and the attribute writes each command makes (as python-ev3dev2 2.1.0)."""

import pytest

from ev3dev2.motor import (
    OUTPUT_A,
    DcMotor,
    LargeMotor,
    MediumMotor,
    ServoMotor,
    SpeedDPM,
    SpeedDPS,
    SpeedInvalid,
    SpeedNativeUnits,
    SpeedPercent,
    SpeedRPM,
    SpeedRPS,
    speed_to_speedvalue,
)

from .fake_brick import medium_motor, tacho_motor


@pytest.fixture
def large(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor(OUTPUT_A)
    brick.clear_log()
    return motor, brick


def test_constructing_reads_max_speed_then_count_per_rot(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA"))
    motor = LargeMotor(OUTPUT_A)

    assert brick.reads() == [("motor0", "max_speed"), ("motor0", "count_per_rot")]
    assert motor.max_rps == pytest.approx(1050 / 360)
    assert motor.max_rpm == pytest.approx(175)
    assert motor.max_dps == pytest.approx(1050)
    assert motor.max_dpm == pytest.approx(63000)


def test_on_for_degrees_sets_position_speed_brake_then_runs(large):
    motor, brick = large
    motor.on_for_degrees(SpeedPercent(50), 360, block=False)

    assert brick.writes() == [
        ("motor0", "position_sp", "360"),
        ("motor0", "speed_sp", "525"),
        ("motor0", "stop_action", "hold"),
        ("motor0", "command", "run-to-rel-pos"),
    ]


def test_negative_speed_with_positive_degrees_drives_backwards(large):
    motor, brick = large
    motor.on_for_degrees(-50, 90, brake=False, block=False)

    assert brick.writes() == [
        ("motor0", "position_sp", "-90"),
        ("motor0", "speed_sp", "525"),
        ("motor0", "stop_action", "coast"),
        ("motor0", "command", "run-to-rel-pos"),
    ]


def test_on_for_rotations_in_rpm(large):
    motor, brick = large
    motor.on_for_rotations(SpeedRPM(30), 2.5, block=False)

    assert brick.writes()[:2] == [("motor0", "position_sp", "900"), ("motor0", "speed_sp", "180")]


def test_on_to_position_rounds_half_to_even_like_upstream(large):
    motor, brick = large
    motor.on_to_position(25, 720, block=False)  # 262.5 native units

    assert brick.writes() == [
        ("motor0", "speed_sp", "262"),
        ("motor0", "position_sp", "720"),
        ("motor0", "stop_action", "hold"),
        ("motor0", "command", "run-to-abs-pos"),
    ]


def test_on_for_seconds_truncates_milliseconds(large):
    motor, brick = large
    motor.on_for_seconds(SpeedDPS(500), 1.2345, block=False)

    assert brick.writes() == [
        ("motor0", "speed_sp", "500"),
        ("motor0", "time_sp", "1234"),
        ("motor0", "stop_action", "hold"),
        ("motor0", "command", "run-timed"),
    ]


def test_on_for_seconds_refuses_negative_time(large):
    motor, brick = large
    with pytest.raises(ValueError, match=r"^seconds is negative \(-1\)$"):
        motor.on_for_seconds(50, -1)
    assert brick.writes() == []


def test_on_and_off(large):
    motor, brick = large
    motor.on(SpeedNativeUnits(-300))
    motor.off(brake=False)

    assert brick.writes() == [
        ("motor0", "speed_sp", "-300"),
        ("motor0", "stop_action", "hold"),
        ("motor0", "command", "run-forever"),
        ("motor0", "stop_action", "coast"),
        ("motor0", "command", "stop"),
    ]


def test_run_commands_set_their_keyword_arguments_first(large):
    motor, brick = large
    motor.run_timed(time_sp=500, speed_sp=300)
    motor.run_direct(duty_cycle_sp=-40)
    motor.reset()

    assert brick.writes() == [
        ("motor0", "time_sp", "500"),
        ("motor0", "speed_sp", "300"),
        ("motor0", "command", "run-timed"),
        ("motor0", "duty_cycle_sp", "-40"),
        ("motor0", "command", "run-direct"),
        ("motor0", "command", "reset"),
    ]


def test_pid_constants_use_the_pid_subfolders(large):
    motor, brick = large
    motor.speed_p = 1000
    motor.position_d = 3
    assert motor.speed_i == 0

    assert brick.log == [
        ["write", "motor0", "speed_pid/Kp", "1000"],
        ["write", "motor0", "hold_pid/Kd", "3"],
        ["read", "motor0", "speed_pid/Ki"],
    ]


def test_blocking_waits_for_running_then_for_not_moving(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA", state=["", "running", "running", ""]))
    motor = LargeMotor(OUTPUT_A)
    brick.clear_log()

    motor.on_for_degrees(50, 90)

    assert [entry for entry in brick.log if entry[0] != "write"] == [
        ["read", "motor0", "state"],
        ["poll", "motor0", "state", 100],
        ["read", "motor0", "state"],
        ["read", "motor0", "state"],
        ["poll", "motor0", "state", 100],
        ["read", "motor0", "state"],
    ]


def test_wait_gives_up_after_its_timeout(make_brick):
    brick = make_brick(tacho_motor("motor0", "outA", state="running"))
    motor = LargeMotor(OUTPUT_A)
    start = brick.clock

    assert motor.wait_while("running", timeout=250) is False
    assert brick.clock - start == pytest.approx(0.3)
    assert motor.wait_until("running", timeout=250) is True


def test_position_in_rotations_and_degrees(make_brick):
    make_brick(tacho_motor("motor0", "outA", position="540"))
    motor = LargeMotor(OUTPUT_A)

    assert motor.rotations == 1.5
    assert motor.degrees == 540.0


def test_medium_motor_has_its_own_max_speed(make_brick):
    brick = make_brick(medium_motor("motor0", "outA"))
    motor = MediumMotor(OUTPUT_A)
    brick.clear_log()

    motor.on(SpeedPercent(10))
    assert brick.writes()[0] == ("motor0", "speed_sp", "156")


def test_speed_percent_out_of_range_is_invalid():
    with pytest.raises(SpeedInvalid) as error:
        SpeedPercent(101)
    assert str(error.value) == "invalid percentage 101, must be between -100 and 100 (inclusive)"
    assert isinstance(error.value, ValueError)
    with pytest.raises(SpeedInvalid):
        SpeedPercent(60) * 2
    with pytest.raises(SpeedInvalid):
        speed_to_speedvalue(-100.5)


def test_speed_units_convert_to_native_units(large):
    motor, brick = large

    assert SpeedPercent(-20).to_native_units(motor) == pytest.approx(-210)
    assert SpeedRPS(1).to_native_units(motor) == pytest.approx(360)
    assert SpeedRPM(60).to_native_units(motor) == pytest.approx(360)
    assert SpeedDPS(90).to_native_units(motor) == pytest.approx(90)
    assert SpeedDPM(5400).to_native_units(motor) == pytest.approx(90)
    assert SpeedNativeUnits(-2000).to_native_units(motor) == -2000  # upstream checks only the upper bound
    assert brick.reads() == []  # max_speed is cached


def test_speed_units_out_of_range_name_the_motor_and_its_limit(large):
    motor, _ = large

    with pytest.raises(
        SpeedInvalid, match=r"^invalid rotations-per-minute: LargeMotor\(ev3-ports:outA\) max RPM is"
    ):
        SpeedRPM(200).to_native_units(motor)
    with pytest.raises(
        SpeedInvalid, match=r"^invalid native-units: LargeMotor\(ev3-ports:outA\) max speed 1050, "
    ):
        SpeedNativeUnits(1051).to_native_units(motor)
    with pytest.raises(SpeedInvalid):
        motor.on(120)


def test_speed_values_multiply_and_print_like_upstream():
    assert (SpeedPercent(20) * 2).percent == 40
    assert (2 * SpeedRPM(10)).rotations_per_minute == 20
    assert str(SpeedPercent(30)) == "30%"
    assert str(SpeedPercent(30, "left_speed")) == "left_speed "  # upstream's operator precedence
    assert str(SpeedNativeUnits(12)) == "12.00 counts/sec"
    assert str(SpeedRPS(2)) == "2 rot/sec"


def test_dc_motor_and_servo_motor(make_brick):
    brick = make_brick(
        {
            "class": "dc-motor",
            "name": "motor0",
            "attrs": {
                "address": "ev3-ports:outC",
                "command": "",
                "time_sp": "0",
                "duty_cycle_sp": "0",
                "stop_action": "",
                "commands": "run-forever run-timed run-direct stop",
            },
        },
        {
            "class": "servo-motor",
            "name": "motor1",
            "attrs": {"address": "ev3-ports:outD", "command": "", "position_sp": "0", "rate_sp": "0"},
        },
    )
    dc = DcMotor("outC")
    dc.run_timed(time_sp=100, duty_cycle_sp=50)
    dc.stop_action = "brake"
    with pytest.raises(Exception, match="^stop_action is a write-only property!$"):
        _ = dc.stop_action
    assert dc.commands == ["run-forever", "run-timed", "run-direct", "stop"]

    servo = ServoMotor("outD")
    servo.run(position_sp=-30)
    servo.float()

    assert brick.writes() == [
        ("motor0", "time_sp", "100"),
        ("motor0", "duty_cycle_sp", "50"),
        ("motor0", "command", "run-timed"),
        ("motor0", "stop_action", "brake"),
        ("motor1", "position_sp", "-30"),
        ("motor1", "command", "run"),
        ("motor1", "command", "float"),
    ]
