"""Motors behave as on a real EV3 (issue 12, "Motors"): whole programs against the ev3dev2 shim.

References:
- ev3dev kernel drivers, github.com/ev3dev/lego-linux-drivers (commit 1b387f3):
  motors/tacho_motor_class.c (the tacho-motor class: attribute docs, tm_send_command, ramps,
  PID attribute store), ev3/legoev3_motor.c (the EV3 motor driver: update_stall, update_position,
  get_state), motors/tacho_motor_helper.c (tm_pid_update), motors/ev3_motor_defs.c (defaults).
- ev3dev tacho-motor class docs: https://docs.ev3dev.org/projects/lego-linux-drivers/en/ev3dev-stretch/motors.html
- python-ev3dev2 2.1.0, ev3dev2/motor.py: Motor.on_for_degrees / on_to_position
  (wait_until('running', timeout=WAIT_RUNNING_TIMEOUT) then wait_until_not_moving, which returns
  once `running` leaves `state` or `stalled` enters it).
"""

import errno

import pytest

from ev3sim2d.devices.motor import TachoMotor
from ev3sim2d.world.robot_spec import default_robot, parse_robot
from ev3sim2d.world.source_error import WorldFileError
from tests.inline_world import arena

DT = 0.01


def lines(result):
    return [line.text for line in result.trace.output]


# -- 1. zero speed, zero distance ------------------------------------------------------------


def test_blocking_moves_with_zero_speed_or_distance_end_as_on_a_brick(run):
    """A run-to-*-pos with speed_sp 0 never moves: the driver keeps it `running`, sees speed 0 and
    reports `stalled` after TACHO_MOTOR_STALLED_MS = 100 ms (legoev3_motor.c update_stall), which
    ends python-ev3dev2's wait_until_not_moving.  A run-to-rel-pos with position_sp 0 is sent as
    a stop (tacho_motor_class.c tm_send_command: "If the relative position setpoint is 0, then
    don't try to run, just stop"), so the only wait is python-ev3dev2's
    wait_until('running', timeout=100).  Neither waits for the run's time limit."""
    result = run(
        """
        import time
        from ev3dev2.motor import LargeMotor, MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent

        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        m = tank.left_motor

        def timed(label, move):
            start = time.time()
            move()
            print(label, round(time.time() - start, 3), m.state.__repr__())

        timed("tank-zero-speed", lambda: tank.on_for_degrees(0, 0, 90))
        timed("motor-zero-speed", lambda: m.on_for_rotations(SpeedPercent(0), 2))
        timed("zero-degrees", lambda: m.on_for_degrees(SpeedPercent(30), 0))
        m.on(50)
        time.sleep(0.5)
        m.off(brake=False)
        timed("zero-degrees-after-coast", lambda: m.on_for_degrees(SpeedPercent(30), 0))
        m.on(50)
        time.sleep(0.5)
        m.off(brake=False)
        timed("zero-speed-after-coast", lambda: m.on_for_degrees(SpeedPercent(0), 90))
        timed("zero-speed-to-position", lambda: m.on_to_position(SpeedPercent(0), m.position + 180))
        """,
        time_limit_s=20,
    )
    assert result.status == "finished", result.status
    out = {line.split()[0]: line.split(maxsplit=2)[1:] for line in lines(result)}
    for label in ("tank-zero-speed", "motor-zero-speed", "zero-speed-after-coast", "zero-speed-to-position"):
        seconds, state = out[label]
        assert 0.1 <= float(seconds) <= 0.2, (label, seconds)
        assert state == "['running', 'stalled']", (label, state)
    for label in ("zero-degrees", "zero-degrees-after-coast"):
        seconds, state = out[label]
        assert float(seconds) <= 0.15, (label, seconds)
        assert "running" not in state, (label, state)
    assert result.sim_time_s < 3.0


# -- 2. ramps ----------------------------------------------------------------------------------


def test_ramp_up_and_ramp_down_are_honoured(run):
    """tacho-motor docs, ramp_up_sp / ramp_down_sp: "the motor speed will increase from 0 to 100% of
    max_speed over the span of this setpoint" (ms), and `ramping` is in `state` "while ramping up or
    down and has not yet reached a constant output level" (tacho_motor_class.c,
    tacho_motor_class_start_motor_ramp; a stop ramps down to 0 first, then applies stop_action)."""
    result = run(
        """
        import time
        from ev3dev2.motor import LargeMotor, OUTPUT_B, SpeedNativeUnits

        m = LargeMotor(OUTPUT_B)
        m.ramp_up_sp = 2000      # 0 -> 1050 deg/s in 2 s, so 0 -> 525 in 1 s
        m.ramp_down_sp = 1000    # 1050 -> 0 in 1 s, so 525 -> 0 in 0.5 s
        m.stop_action = 'brake'
        m.speed_sp = 525
        m.run_forever()
        time.sleep(0.5)
        print('up-half', m.speed, ' '.join(m.state))
        time.sleep(1.0)
        print('up-done', m.speed, ' '.join(m.state))
        m.stop()
        time.sleep(0.25)
        print('down-half', m.speed, ' '.join(m.state))
        time.sleep(0.5)
        print('down-done', m.speed, ' '.join(m.state))
        before = m.position
        m.on_for_degrees(SpeedNativeUnits(525), 720)
        print('landed', m.position - before, ' '.join(m.state))
        """,
        time_limit_s=20,
    )
    assert result.status == "finished", result.status
    out = {line.split()[0]: line.split()[1:] for line in lines(result)}
    speed, *state = out["up-half"]
    assert 200 <= int(speed) <= 300 and state == ["running", "ramping"], out["up-half"]
    speed, *state = out["up-done"]
    assert int(speed) == 525 and state == ["running"], out["up-done"]
    speed, *state = out["down-half"]
    assert 200 <= int(speed) <= 300 and state == ["running", "ramping"], out["down-half"]
    speed, *state = out["down-done"]
    assert int(speed) == 0 and state == [], out["down-done"]
    moved, *state = out["landed"]
    assert abs(int(moved) - 720) <= 1 and state == ["holding"], out["landed"]


def test_a_ramped_move_takes_longer_and_still_lands(run):
    """With ramp_up_sp and ramp_down_sp the motor accelerates and decelerates linearly
    (tacho-motor docs, ramp_up_sp / ramp_down_sp; legoev3_motor.c update_position ramps down to
    land on position_sp), so a move takes longer than the same move without ramps, and still ends
    on its target."""
    program = """
        import time
        from ev3dev2.motor import LargeMotor, OUTPUT_B, SpeedNativeUnits

        m = LargeMotor(OUTPUT_B)
        m.ramp_up_sp = {ramp}
        m.ramp_down_sp = {ramp}
        start = time.time()
        m.on_for_degrees(SpeedNativeUnits(1050), 1050)
        print(round(time.time() - start, 2), m.position)
    """
    plain = run(program.format(ramp=0))
    ramped = run(program.format(ramp=1000))
    plain_s, plain_pos = lines(plain)[-1].split()
    ramped_s, ramped_pos = lines(ramped)[-1].split()
    assert abs(int(plain_pos) - 1050) <= 1 and abs(int(ramped_pos) - 1050) <= 1
    assert 0.95 <= float(plain_s) <= 1.2  # 1050 deg at 1050 deg/s
    # 1 s up to full speed (525 deg), 1 s down (525 deg): 2 s, no cruise
    assert 1.9 <= float(ramped_s) <= 2.2


# -- 3. overload -------------------------------------------------------------------------------


def test_a_motor_blocked_at_high_power_is_overloaded_and_pushes_harder(run):
    """The speed PID (tacho_motor_helper.c tm_pid_update) adds up the error of a blocked shaft until
    its output passes 100 %: then the driver reports `overloaded` (legoev3_motor.c get_state:
    speed_pid_ena && tm_pid_is_overloaded) and the duty cycle is clamped at 100; `stalled` comes
    after 100 ms without motion (update_stall)."""
    world = arena(start="x_cm: 200\n  y_cm: 120\n  heading_deg: 0")
    result = run(
        """
        import time
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C

        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(90, 90)
        time.sleep(0.1)
        print('free', tank.left_motor.duty_cycle, ' '.join(tank.left_motor.state))
        tank.left_motor.wait_until('stalled', timeout=5000)
        time.sleep(0.2)
        print('blocked', tank.left_motor.duty_cycle, ' '.join(tank.left_motor.state))
        tank.off()
        """,
        world,
    )
    assert result.status == "finished", result.status
    out = {line.split()[0]: line.split()[1:] for line in lines(result)}
    free_duty, *free_state = out["free"]
    assert 80 <= int(free_duty) <= 100 and free_state == ["running"], out["free"]
    duty, *state = out["blocked"]
    assert int(duty) == 100, out["blocked"]
    assert state == ["running", "overloaded", "stalled"], out["blocked"]


# -- 4. PID defaults and their checks ---------------------------------------------------------


def test_pid_defaults_are_the_drivers_and_negative_gains_are_refused(run):
    """lego-linux-drivers motors/ev3_motor_defs.c: lego-ev3-l-motor speed_pid_k {p 1000, i 60, d 0},
    position_pid_k (hold_pid) {p 80000, i 0, d 0}; lego-ev3-m-motor the same but hold Kp 160000.
    tacho_motor_class.c PID_ATTR_FUNCS name##_store: `if (k < 0) return -EINVAL;`, which
    python-ev3dev2 (ev3dev2/__init__.py _raise_friendly_access_error) turns into a ValueError."""
    result = run("""
        from ev3dev2.motor import LargeMotor, MediumMotor, OUTPUT_A, OUTPUT_B

        for m in (LargeMotor(OUTPUT_B), MediumMotor(OUTPUT_A)):
            print(m.driver_name, m.speed_p, m.speed_i, m.speed_d, m.position_p, m.position_i, m.position_d)
            try:
                m.position_p = -5
            except ValueError:
                print('refused', m.position_p)
            m.speed_i = 0
            m.reset()
            print('after-reset', m.speed_i)
    """)
    assert result.status == "finished", result.status
    assert lines(result) == [
        "lego-ev3-l-motor 1000 60 0 80000 0 0",
        "refused 80000",
        "after-reset 60",
        "lego-ev3-m-motor 1000 60 0 160000 0 0",
        "refused 160000",
        "after-reset 60",
    ]


@pytest.mark.parametrize("pid", ["hold_pid/Kp", "hold_pid/Ki", "hold_pid/Kd", "speed_pid/Kp", "speed_pid/Ki"])
def test_a_negative_pid_gain_is_einval(pid):
    """tacho_motor_class.c PID_ATTR_FUNCS: a negative gain is refused with EINVAL; 0 is accepted."""
    m = TachoMotor("ev3-ports:outB", "large")
    with pytest.raises(OSError) as err:
        m.write(pid, "-1")
    assert err.value.errno == errno.EINVAL
    m.write(pid, "0")
    assert m.read(pid) == "0"


# -- 5. motors mounted the other way round ---------------------------------------------------

REVERSED_ROBOT = """\
name: reversed base
wheel_diameter_mm: 56
axle_track_mm: 120
body: {front_cm: 9, back_cm: 7, width_cm: 15}
motors:
  - {port: B, kind: large, wheel: left, mounted: reversed}
  - {port: C, kind: large, wheel: right, mounted: reversed}
"""


def test_a_robot_whose_motors_face_backwards_drives_forward_with_inversed_polarity(run):
    """ev3dev tacho-motor docs, polarity: "inversed" makes a positive speed_sp turn the motor the
    other way (counter-clockwise); a program for a robot whose motors are mounted backwards sets
    it so that positive speeds drive forward.  The robot file's `mounted: reversed` says so."""
    robot = parse_robot(REVERSED_ROBOT, "reversed.yaml")
    assert robot.left_wheel.reversed and robot.right_wheel.reversed
    source = """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        {setup}
        tank.on_for_rotations(SpeedPercent(50), SpeedPercent(50), 1)
        print(tank.left_motor.position, tank.right_motor.position)
    """
    inversed = "tank.left_motor.polarity = 'inversed'; tank.right_motor.polarity = 'inversed'"
    forward = run(source.format(setup=inversed), robot=robot)
    backward = run(source.format(setup="pass"), robot=robot)
    one_turn_cm = 3.14159 * 5.6
    x_forward = forward.trace.poses(0)[-1][0]
    x_backward = backward.trace.poses(0)[-1][0]
    assert abs(x_forward - (60 + one_turn_cm)) < 0.5, x_forward
    assert abs(x_backward - (60 - one_turn_cm)) < 0.5, x_backward
    assert lines(forward)[-1] == "360 360" and lines(backward)[-1] == "360 360"


def test_mounted_is_checked_with_the_file_and_line():
    """Our robot file format (docs/world-files.md, "Robot files"): a wrong `mounted` is reported as
    file:line:column with the allowed words, as every other mistake in a robot file is."""
    text = REVERSED_ROBOT.replace("mounted: reversed}\n  - {port: C", "mounted: reverse}\n  - {port: C")
    with pytest.raises(WorldFileError) as err:
        parse_robot(text, "reversed.yaml")
    message = str(err.value)
    assert message.startswith("reversed.yaml:6:"), message
    assert "did you mean 'reversed'" in message and "normal, reversed" in message


def test_motors_are_mounted_normally_by_default():
    """docs/world-files.md: `mounted` defaults to `normal`; the shipped driving base has no reversed motor."""
    robot = default_robot()
    assert not any(m.reversed for m in robot.motors)
