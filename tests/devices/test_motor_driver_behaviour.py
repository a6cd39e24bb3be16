"""Four things the EV3 motor does that only the drivers' code says: whole programs against the ev3dev2
shim, on a medium motor (outA) that drives no wheel.

References: ev3dev kernel drivers, github.com/ev3dev/lego-linux-drivers, ev3dev-buster at 1b387f3
(ev3dev-stretch, which most bricks run, has the same lines); python-ev3dev2 2.1.0, ev3dev2/motor.py
(on_for_degrees / on_to_position: run_to_rel_pos / run_to_abs_pos, then wait_until_not_moving;
brake=True is stop_action hold, brake=False coast; reset() writes command=reset).
"""

import pytest

from ev3sim2d.world.robot_spec import parse_robot

ROBOT = """\
name: robot with an arm
wheel_diameter_mm: 56
axle_track_mm: 120
body: {front_cm: 9, back_cm: 7, width_cm: 15}
motors:
  - {port: B, kind: large, wheel: left}
  - {port: C, kind: large, wheel: right}
  - {port: A, kind: medium}
"""


@pytest.fixture
def run_arm(run):
    """run_arm(source) -> {first word of each printed line: the rest}: the program run on the robot."""

    def _run(source: str) -> dict[str, list[str]]:
        result = run(source, robot=parse_robot(ROBOT), time_limit_s=20)
        assert result.status == "finished", result.reason
        return {line.text.split()[0]: line.text.split()[1:] for line in result.trace.output}

    return _run


def test_inversing_the_polarity_negates_what_position_and_the_setpoints_read(run_arm):
    """motors/tacho_motor_class.c:866 polarity_store only sets tm->polarity (:874); the count and the
    setpoints stay as stored, in the motor's frame, and are negated each time they are read or written
    while the polarity is inversed: position_show :461 (the negation at :471), position_store :477,
    duty_cycle_show :558, speed_show :585, duty_cycle_sp_show :947 / _store :959, speed_sp_show :990 /
    _store :1002, position_sp_show :1052 / _store :1064.  So the shaft stays where it is, position
    90 reads -90, and a speed_sp written before the change reads negated and still turns the shaft the
    same way.  ev3sim2d kept position and the setpoints as they read, and turned the shaft backwards."""
    out = run_arm(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A

        arm = MediumMotor(OUTPUT_A)
        arm.duty_cycle_sp = 40
        arm.run_to_abs_pos(position_sp=90, speed_sp=300, stop_action='hold')
        arm.wait_while('running')
        print('normal', arm.position, arm.position_sp, arm.speed_sp, arm.duty_cycle_sp)
        arm.polarity = 'inversed'
        print('inversed', arm.position, arm.position_sp, arm.speed_sp, arm.duty_cycle_sp)
        arm.run_forever()
        time.sleep(0.5)
        print('running', arm.position, arm.speed)
        arm.stop(stop_action='brake')
        arm.position_sp = 30  # stored as -30 in the motor's frame
        arm.polarity = 'normal'
        print('normal-again', arm.position, arm.position_sp, arm.speed_sp)
        """
    )
    assert out["normal"] == ["90", "90", "300", "40"]
    assert out["inversed"] == ["-90", "-90", "-300", "-40"]
    # speed_sp 300 as stored: the shaft turns on forward (count 90 -> about 240), read negated
    position, speed = (int(value) for value in out["running"])
    assert -250 <= position <= -230 and speed == -300
    stopped_at, position_sp, speed_sp = (int(value) for value in out["normal-again"])
    assert -position <= stopped_at <= -position + 10 and (position_sp, speed_sp) == (-30, 300)


def test_position_can_be_written_while_the_motor_runs_and_ends_a_run_to_a_position(run_arm):
    """ev3/legoev3_motor.c:326 legoev3_motor_set_position refuses with EBUSY only
    `if (legoev3_motor_get_state(ev3_tm) & TM_STATE_RUNNING)` (:330); but get_state sets
    BIT(TM_STATE_RUNNING) (:382) and TM_STATE_RUNNING is the enum's first value, 0
    (include/tacho_motor_class.h:56), so the test is `state & 0`, never true: the write is accepted
    while the motor runs (so on every branch since 1f4fc8d, 2015).  It renumbers the count
    (position_offset) and sets the run to a position's target to the written value
    (`ev3_tm->position_sp = position`, :336); update_position, at the next encoder reading, finds it
    reached (:238, :251) and stops the motor there with the run's stop action.  ev3sim2d let the run
    go on to its old target."""
    out = run_arm(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        arm = MediumMotor(OUTPUT_A)
        arm.on(SpeedPercent(20))
        time.sleep(0.5)
        arm.position = 1000
        time.sleep(0.5)
        print('forever', arm.position, *arm.state)
        arm.off()
        arm.position = 0
        arm.on_to_position(SpeedPercent(20), 720, block=False)
        time.sleep(0.5)
        arm.position = 0
        time.sleep(0.5)
        print('to-position', arm.position, arm.speed, *arm.state)
        """
    )
    assert out["forever"] == ["1156", "running"]  # 20 % of 1560 counts/s for 0.5 s after the write
    assert out["to-position"] == ["0", "0", "holding"]


def test_a_run_to_rel_pos_after_a_run_to_rel_pos_counts_from_its_target(run_arm):
    """motors/tacho_motor_class.c:646 tm_send_command: for run-to-rel-pos, `if (tm->params.command ==
    TM_COMMAND_RUN_TO_REL_POS)` (:680), the new target is `tm->active_params.position_sp +
    tm->params.position_sp` (:693), the previous run's target plus position_sp; otherwise the position
    now plus position_sp (:698-:700).  tm->params.command is the last command written (command_store,
    :782), whether that run is still going, ended or stalled; any other command (stop, reset, run-*)
    ends the chain, and writing position does not.  So a move that coasted past its target
    (brake=False) is made up by the next.  ev3sim2d counted every move from where the shaft was."""
    out = run_arm(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        arm = MediumMotor(OUTPUT_A)
        arm.on_for_degrees(SpeedPercent(30), 360, brake=False)
        time.sleep(0.5)
        print('coasted', arm.position)
        arm.on_for_degrees(SpeedPercent(30), 360)
        print('chained', arm.position)
        arm.on_for_degrees(SpeedPercent(30), 90, brake=False)
        time.sleep(0.5)
        coasted = arm.position
        arm.stop()
        arm.on_for_degrees(SpeedPercent(30), 90)
        print('after-stop', arm.position - coasted)
        """
    )
    assert int(out["coasted"][0]) > 370  # rolled on past 360
    assert out["chained"] == ["720"]  # 360 + 360, not where it rolled to + 360
    assert out["after-stop"] == ["90"]  # a stop in between: from where it is


def test_reset_coasts_a_turning_motor_to_a_stop(run_arm):
    """ev3/legoev3_motor.c:169 legoev3_motor_reset stops the motor with
    `__legoev3_motor_stop(ev3_tm, TM_STOP_ACTION_COAST)` (:176), then `position_offset = -position`
    (:179): position reads 0 from where the shaft was and counts on as the motor rolls out; the
    settings go back to their defaults (tacho_motor_class.c, tacho_motor_class_reset).  ev3sim2d
    stopped the shaft dead."""
    out = run_arm(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        arm = MediumMotor(OUTPUT_A)
        arm.on(SpeedPercent(50))
        time.sleep(0.5)
        arm.reset()
        print('reset', arm.speed, arm.speed_sp, repr(arm.state))
        time.sleep(1)
        print('later', arm.position, arm.speed, repr(arm.state))
        """
    )
    assert out["reset"] == ["780", "0", "[]"]  # still turning at 50 % of 1560, coasting
    rolled, speed, state = out["later"]
    assert 40 <= int(rolled) <= 80 and (speed, state) == ("0", "[]")  # 780 deg/s x 80 ms, counted from 0
