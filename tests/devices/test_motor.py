"""The simulated tacho motor: commands, exact run ends, stop actions, stall, attribute errors."""

import errno

import pytest

from ev3sim2d.devices.motor import TachoMotor

DT = 0.01


def turn_freely(motor, ticks):
    for _ in range(ticks):
        planned = motor.plan(DT)
        motor.measured(planned, planned, DT)


def test_defaults_match_an_ev3_large_motor():
    m = TachoMotor("ev3-ports:outB", "large")
    assert m.read("driver_name") == "lego-ev3-l-motor"
    assert m.read("max_speed") == "1050"
    assert m.read("count_per_rot") == "360"
    assert m.read("state") == ""
    assert m.read("stop_action") == "coast"
    assert TachoMotor("ev3-ports:outA", "medium").read("max_speed") == "1560"


def test_run_to_rel_pos_lands_exactly_and_holds():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("position_sp", "725")
    m.write("speed_sp", "500")
    m.write("stop_action", "hold")
    m.write("command", "run-to-rel-pos")
    assert m.read("state") == "running"
    turn_freely(m, 200)
    assert m.read("position") == "725"
    assert m.read("state") == "holding"
    m.write("command", "run-to-rel-pos")  # relative to where it is now
    turn_freely(m, 200)
    assert m.read("position") == "1450"


def test_negative_speed_still_reaches_an_absolute_target():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("position_sp", "-90")
    m.write("speed_sp", "-300")
    m.write("stop_action", "hold")
    m.write("command", "run-to-abs-pos")
    turn_freely(m, 100)
    assert m.read("position") == "-90"


def test_run_to_position_with_coast_rolls_a_little_past_the_target():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("position_sp", "360")
    m.write("speed_sp", "300")
    m.write("command", "run-to-rel-pos")
    turn_freely(m, 200)
    assert 360 < int(m.read("position")) < 400


def test_run_timed_turns_for_exactly_time_sp():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("speed_sp", "360")
    m.write("time_sp", "1234")
    m.write("stop_action", "brake")
    m.write("command", "run-timed")
    turn_freely(m, 300)
    assert m.read("position") == str(round(360 * 1.234))
    assert m.read("state") == ""


def test_coast_rolls_out_briefly_brake_stops_at_once():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("speed_sp", "1000")
    m.write("command", "run-forever")
    turn_freely(m, 10)
    at_stop = int(m.read("position"))
    m.write("stop_action", "coast")
    m.write("command", "stop")
    turn_freely(m, 100)
    rolled = int(m.read("position")) - at_stop
    assert 20 < rolled < 150
    assert m.read("speed") == "0"

    m.write("command", "run-forever")
    turn_freely(m, 10)
    at_stop = int(m.read("position"))
    m.write("stop_action", "brake")
    m.write("command", "stop")
    turn_freely(m, 10)
    assert int(m.read("position")) == at_stop


def test_a_blocked_shaft_reports_stalled():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("speed_sp", "500")
    m.write("command", "run-forever")
    for _ in range(20):
        m.measured(m.plan(DT), 0.0, DT)
    assert m.read("state") == "running overloaded stalled"  # the speed PID pushes to 100 %
    assert m.read("duty_cycle") == "100"
    turn_freely(m, 1)
    assert m.read("state") == "running"
    assert m.read("duty_cycle") == "48"


def test_inversed_polarity_turns_the_other_way_and_counts_in_its_own_frame():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("polarity", "inversed")
    m.write("speed_sp", "100")
    m.write("command", "run-forever")
    planned = m.plan(DT)
    assert planned < 0
    m.measured(planned, planned, DT)
    assert m.read("position") == "1"


@pytest.mark.parametrize(
    "attribute, value",
    [
        ("speed_sp", "1051"),
        ("command", "fly"),
        ("stop_action", "park"),
        ("time_sp", "-1"),
        ("duty_cycle_sp", "101"),
    ],
)
def test_invalid_values_are_refused_like_the_driver_does(attribute, value):
    m = TachoMotor("ev3-ports:outB", "large")
    with pytest.raises(OSError) as err:
        m.write(attribute, value)
    assert err.value.errno == errno.EINVAL


def test_unknown_and_read_only_attributes():
    m = TachoMotor("ev3-ports:outB", "large")
    with pytest.raises(OSError) as err:
        m.read("colour")
    assert err.value.errno == errno.ENOENT
    with pytest.raises(OSError) as err:
        m.write("max_speed", "5")
    assert err.value.errno == errno.EACCES


def test_a_ramp_changes_speed_linearly_and_passes_through_zero_when_reversing():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("ramp_up_sp", "1000")  # 1050 deg/s per second up
    m.write("ramp_down_sp", "500")  # 2100 deg/s per second down
    m.write("speed_sp", "525")
    m.write("command", "run-forever")
    turn_freely(m, 25)
    assert m.read("speed") == "257" and m.read("state") == "running ramping"  # the last tick's mean
    turn_freely(m, 30)
    assert m.read("speed") == "525" and m.read("state") == "running"
    assert m.mode == "run"  # done ramping: no more ramp work each tick
    m.write("speed_sp", "-525")
    m.write("command", "run-forever")
    turn_freely(m, 30)  # 0.25 s down to 0, then 0.05 s up the other way at the ramp-up rate
    assert -60 < int(m.read("speed")) < -40 and m.read("state") == "running ramping"
    turn_freely(m, 60)
    assert m.read("speed") == "-525" and m.read("state") == "running"


def test_a_ramped_run_to_position_lands_exactly_and_a_timed_run_ramps_down_after_time_sp():
    m = TachoMotor("ev3-ports:outB", "large")
    m.write("ramp_up_sp", "1000")
    m.write("ramp_down_sp", "1000")
    m.write("speed_sp", "700")
    m.write("position_sp", "1000")
    m.write("stop_action", "hold")
    m.write("command", "run-to-abs-pos")
    turn_freely(m, 400)
    assert m.read("position") == "1000" and m.read("state") == "holding"
    m.write("speed_sp", "525")
    m.write("time_sp", "1000")
    m.write("command", "run-timed")
    turn_freely(m, 100)
    assert m.read("state") == "running ramping"  # time_sp is over: the ramp down to 0 starts
    turn_freely(m, 60)
    assert m.read("state") == "holding" and m.read("speed") == "0"
    # 0.5 s up (131 deg), 0.5 s at 525 (262 deg), 0.5 s down (131 deg)
    assert abs(int(m.read("position")) - 1000 - 525) <= 3
