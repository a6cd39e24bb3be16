"""A motor that drives no wheel (an arm, a gripper, a launcher) meets its end stops and its load as on a
real EV3: whole programs against the ev3dev2 shim, robots written in the test's folder.

References:
- ev3dev kernel drivers, github.com/ev3dev/lego-linux-drivers (commit 1b387f3): ev3/legoev3_motor.c
  (update_stall: `stalled` once `speed == 0` for more than TACHO_MOTOR_STALLED_MS = 100 ms while the
  motor runs; legoev3_motor_get_state: `running`, plus `overloaded` while the speed PID is
  saturated, plus `stalled`; update_position: a run to a position stops only when the position
  reaches position_sp; legoev3_motor_reset: position_offset = -position, the shaft does not move),
  motors/tacho_motor_class.c (the attribute docs: state flags, max_speed, stop_action).
- python-ev3dev2 2.1.0, ev3dev2/motor.py: Motor.on_to_position (run_to_abs_pos, then
  wait_until('running') and wait_until_not_moving, which returns once `running` leaves `state` or
  `stalled` enters it), Motor.on (run_forever), Motor.wait_until, Motor.is_stalled.
"""

import pytest

from ev3sim2d.world.robot_spec import load_robot, parse_robot
from ev3sim2d.world.source_error import WorldFileError

ROBOT = """\
name: robot with an arm
wheel_diameter_mm: 56
axle_track_mm: 120
body: {{front_cm: 9, back_cm: 7, width_cm: 15}}
motors:
  - {{port: B, kind: large, wheel: left}}
  - {{port: C, kind: large, wheel: right}}
  - {{port: A, kind: medium{arm}}}
"""


def robot_with_arm(tmp_path, arm: str):
    """The driving base with a medium motor on outA, its robot-file entry ending in `arm`."""
    path = tmp_path / "arm-robot.yaml"
    path.write_text(ROBOT.format(arm=arm), encoding="utf-8")
    return load_robot(path)


def printed(result) -> dict[str, list[str]]:
    assert result.status == "finished", result.reason
    return {line.text.split()[0]: line.text.split()[1:] for line in result.trace.output}


def test_a_run_to_a_position_past_the_end_stop_stalls_there_as_on_a_brick(run, tmp_path):
    """legoev3_motor.c: against the stop the shaft's speed is 0, so after 100 ms update_stall sets
    `stalled`; the speed PID pushes to full duty, so `overloaded` (tacho-motor docs: "The motor is
    turning as fast as possible, but cannot reach its speed_sp"); and update_position never sees
    position_sp reached, so the run goes on, `running` stays in `state`, until the program stops the
    motor.  python-ev3dev2's on_to_position returns as soon as `stalled` shows.  Today the arm turns
    on to -180 as if nothing were in its way."""
    robot = robot_with_arm(tmp_path, ", limits_deg: [-90, 0]")
    result = run(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        arm = MediumMotor(OUTPUT_A)
        start = time.time()
        arm.on_to_position(SpeedPercent(30), -180)
        print('returned', round(time.time() - start, 3), arm.position, arm.speed, arm.duty_cycle, *arm.state)
        time.sleep(0.5)
        print('later', arm.position, arm.speed, arm.is_stalled, *arm.state)
        arm.off()
        time.sleep(0.2)
        print('off', arm.position, *arm.state)
        arm.on_to_position(SpeedPercent(30), -45)
        print('back', arm.position, *arm.state)
        """,
        robot=robot,
        time_limit_s=20,
    )
    out = printed(result)
    seconds, position, speed, duty, *state = out["returned"]
    # 90 degrees at 30 % of 1560 deg/s (0.19 s), then 100 ms standing still, then the brick's sample
    assert 0.29 <= float(seconds) <= 0.35, seconds
    assert (int(position), int(speed), int(duty)) == (-90, 0, -100)
    assert state == ["running", "overloaded", "stalled"]
    assert out["later"] == ["-90", "0", "True", "running", "overloaded", "stalled"]
    assert out["off"] == ["-90", "holding"]
    assert out["back"] == ["-45", "holding"]


def test_grab_until_stalled_returns_at_the_end_stop(run, tmp_path):
    """A gripper closed with python-ev3dev2's MediumMotor.on(...) and wait_until('stalled'), as grab
    programs do: the jaws meet at the end stop, the speed falls to 0 and 100 ms later the driver says
    `stalled` (legoev3_motor.c update_stall); the motor still runs, overloaded, until it is stopped.
    Today the shaft never stops, so wait_until gives up at its timeout."""
    robot = robot_with_arm(tmp_path, ", limits_deg: [0, 120]")
    result = run(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        gripper = MediumMotor(OUTPUT_A)
        gripper.on(SpeedPercent(40))
        start = time.time()
        stalled = gripper.wait_until('stalled', timeout=3000)
        print('grabbed', stalled, round(time.time() - start, 3), gripper.position, gripper.speed, *gripper.state)
        gripper.off(brake=False)
        print('released', gripper.position, gripper.speed, gripper.state)
        """,
        robot=robot,
        time_limit_s=20,
    )
    out = printed(result)
    stalled, seconds, position, speed, *state = out["grabbed"]
    assert stalled == "True"
    assert 0.25 <= float(seconds) <= 0.35, seconds  # 120 degrees at 624 deg/s, then 100 ms still
    assert (int(position), int(speed)) == (120, 0)
    assert state == ["running", "overloaded", "stalled"]
    assert out["released"] == ["120", "0", "[]"]


def test_a_load_slows_the_motor_and_can_stall_it(run, tmp_path):
    """tacho-motor docs, max_speed: "the speed of the motor at 9V with no load ... The actual maximum
    obtainable speed will be less than this and will depend on ... mechanical load on the motor", and
    `overloaded`: "turning as fast as possible, but cannot reach its speed_sp".  A load of 40 % of the
    stall torque: the speed PID reaches 40 % of max_speed at 80 % duty, but 90 % only as far as 60 %
    (full duty less the load), overloaded, not stalled (it turns); run-direct at 50 % turns at 10 %,
    and at 30 % cannot turn it at all: `stalled` (speed 0 for 100 ms, update_stall).  Today a load is
    refused in a robot file."""
    robot = robot_with_arm(tmp_path, ", load_pct: 40")
    result = run(
        """
        import time
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        m = MediumMotor(OUTPUT_A)
        m.on(SpeedPercent(40))
        time.sleep(0.5)
        print('slow', m.speed, m.duty_cycle, *m.state)
        m.on(SpeedPercent(90))
        time.sleep(0.5)
        print('fast', m.speed, m.duty_cycle, *m.state)
        m.run_direct(duty_cycle_sp=50)
        time.sleep(0.5)
        print('direct50', m.speed, *m.state)
        m.run_direct(duty_cycle_sp=30)
        time.sleep(0.5)
        print('direct30', m.speed, *m.state)
        m.off()
        """,
        robot=robot,
        time_limit_s=20,
    )
    out = printed(result)
    assert out["slow"] == ["624", "80", "running"]
    assert out["fast"] == ["936", "100", "running", "overloaded"]
    assert out["direct50"] == ["156", "running"]
    assert out["direct30"] == ["0", "running", "stalled"]


def test_the_end_stops_do_not_move_when_the_position_is_reset(run, tmp_path):
    """legoev3_motor.c legoev3_motor_reset: position_offset = -position, so `position` reads 0 but the
    shaft stays where it is; the end stop is where it was.  An arm stalled at its stop (-90), reset,
    cannot turn a further -10 degrees.  Today it turns freely."""
    robot = robot_with_arm(tmp_path, ", limits_deg: [-90, 90]")
    result = run(
        """
        from ev3dev2.motor import MediumMotor, OUTPUT_A, SpeedPercent

        arm = MediumMotor(OUTPUT_A)
        arm.on_for_degrees(SpeedPercent(30), -120)
        print('down', arm.position, *arm.state)
        arm.reset()
        arm.on_for_degrees(SpeedPercent(30), -10)
        print('further', arm.position, *arm.state)
        arm.on_for_degrees(SpeedPercent(30), 170)
        print('up', arm.position, *arm.state)
        """,
        robot=robot,
        time_limit_s=20,
    )
    out = printed(result)
    assert out["down"] == ["-90", "running", "overloaded", "stalled"]
    assert out["further"] == ["0", "running", "overloaded", "stalled"]
    # from -90 to +70, inside the stops: a run-to-rel-pos after a run-to-rel-pos counts from that one's
    # target (-10, never reached at the stop), not from where the shaft is (tm_send_command), so 160
    assert out["up"] == ["160", "holding"]


@pytest.mark.parametrize(
    "arm, wheel, message",
    [
        (", limits_deg: [0, -90]", "", "8:41: 'limits_deg' is [low, high] with low below high"),
        (
            ", limits_deg: [10, 90]",
            "",
            "8:41: the shaft starts at 0 degrees, which must lie within its limits",
        ),
        (
            ", limits_deg: 90",
            "",
            "8:41: 'limits_deg' must be a list, got '90'; write e.g. `limits_deg: [-90, 0]`",
        ),
        (
            ", load_pct: 150",
            "",
            "8:39: 'load_pct' is the torque of the load on the shaft in % of the motor's",
        ),
        (", limits: [-90, 0]", "", "8:29: unknown key 'limits' in 'motor'; did you mean 'limits_deg'?"),
        ("", ", load_pct: 5", "6:41: 'load_pct' is for a motor that drives no wheel (an arm, a gripper"),
    ],
)
def test_a_mistake_in_the_end_stops_or_the_load_names_the_line_and_the_fix(arm, wheel, message):
    """docs/world-files.md: every mistake in a robot file is reported as `file:line:column: what is
    wrong; what to write instead`.  Today these keys are unknown ones."""
    text = ROBOT.format(arm=arm).replace("wheel: left}", f"wheel: left{wheel}}}")
    with pytest.raises(WorldFileError) as caught:
        parse_robot(text, "arm.yaml")
    assert f"arm.yaml:{message}" in str(caught.value)
