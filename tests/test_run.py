"""Whole runs: a program drives the robot in a world, as a student would run it."""

import math
import sys

import pytest

from tests.inline_world import arena

WHEEL_CIRCUMFERENCE_CM = math.pi * 5.6


def end_pose(result):
    x, y, heading = result.trace.poses(0)[-1]
    return x, y, heading


def test_two_wheel_rotations_drive_two_circumferences(run):
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(SpeedPercent(50), SpeedPercent(50), 2)
    """)
    assert result.status == "finished"
    x, y, heading = end_pose(result)
    assert abs((x - 60) - 2 * WHEEL_CIRCUMFERENCE_CM) < 0.01 * 2 * WHEEL_CIRCUMFERENCE_CM
    assert abs(y - 120) < 0.1 and abs(heading) < 0.5


def test_a_full_spin_measured_by_the_gyro(run):
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import GyroSensor
        gyro = GyroSensor()
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(20, -20)
        while gyro.angle < 360:
            pass
        tank.off()
        print(gyro.angle)
    """)
    assert result.status == "finished"
    angle = int(result.trace.output[-1].text)
    assert 360 <= angle <= 366
    _, _, heading = end_pose(result)
    assert math.isclose(heading, -angle, abs_tol=3)  # clockwise on the gyro is negative heading


def test_a_blocking_move_into_a_wall_ends_stalled(run):
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on_for_rotations(SpeedPercent(40), SpeedPercent(40), 20)
        print(tank.left_motor.is_stalled, tank.left_motor.position)
    """)
    assert result.status == "finished"
    stalled, position = result.trace.output[-1].text.split()
    assert stalled == "True"
    assert int(position) < 20 * 360 * 0.9
    x, _, _ = end_pose(result)
    front = 9.0
    assert abs(x + front - (20 - 1) * 12) < 1.0  # body front at the wall's face
    assert result.sim_time_s < 20 * 360 / 420  # far less than the 20 rotations would take


def test_a_robot_meeting_a_wall_at_an_angle_glides_along_it(run):
    world = arena(start="x_cm: 60\n  y_cm: 180\n  heading_deg: 30")
    result = run(
        """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(50, 50, 4)
    """,
        world,
    )
    x, y, heading = end_pose(result)
    top_face = 19 * 12
    assert y < top_face  # still inside
    assert x > 60 + 4 * 0.5 * 525 / 360 * WHEEL_CIRCUMFERENCE_CM * math.cos(math.radians(30)) * 0.8
    contacts = result.trace.motion()[:, 3]
    assert contacts.any()


def test_an_empty_port_raises_device_not_found_like_a_brick(run):
    result = run("""
        from ev3dev2.motor import LargeMotor, OUTPUT_D
        m = LargeMotor(OUTPUT_D)
    """)
    assert result.status == "error"
    assert result.error["type"] == "DeviceNotFound"
    assert result.error["message"] == "LargeMotor(ev3-ports:outD) is not connected."
    assert result.error["line"] == 3
    assert "outB large motor" in result.error["hint"]


def test_a_device_of_another_type_is_not_found_either(run):
    result = run("""
        from ev3dev2.sensor.lego import ColorSensor
        from ev3dev2.sensor import INPUT_4
        ColorSensor(INPUT_4)
    """)
    assert result.error["type"] == "DeviceNotFound"


def test_same_program_world_and_seed_give_the_same_run(run):
    source = """
        from ev3dev2.motor import MoveSteering, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import UltrasonicSensor
        us = UltrasonicSensor()
        steer = MoveSteering(OUTPUT_B, OUTPUT_C)
        while us.distance_centimeters > 20:
            steer.on(-4, 40)
        steer.off()
    """
    a, b = run(source), run(source)
    assert a.status == b.status == "finished"
    assert a.trace.fingerprint() == b.trace.fingerprint()
    assert len(a.trace.times) > 10


def test_an_exception_points_into_the_program_with_the_time(run):
    result = run("""
        import time
        time.sleep(1.5)
        x = 1 / 0
    """)
    assert result.status == "error"
    assert result.error["type"] == "ZeroDivisionError"
    assert result.error["line"] == 4
    assert result.error["file"].endswith(".py")
    assert "line 4" in result.error["traceback"]
    assert "ev3sim2d" not in result.error["traceback"]
    assert math.isclose(result.sim_time_s, 1.5)
    assert "at 1.50 s" in result.reason


@pytest.mark.parametrize(
    "loop",
    [
        "import _thread\nlock = _thread.allocate_lock()\nlock.acquire()\nlock.acquire()\n",
        "import os\nr, w = os.pipe()\nos.read(r, 1)\n",
    ],
)
def test_a_program_that_spins_without_the_robot_or_clock_is_stopped(run, loop):
    result = run(loop, hang_after_s=0.5)
    assert result.status == "hung"
    assert "without using the robot or the clock" in result.reason


def test_the_run_ends_at_the_time_limit(run):
    result = run(
        """
        import time
        while True:
            time.sleep(0.1)
    """,
        time_limit_s=2.0,
    )
    assert result.status == "time_limit"
    assert result.sim_time_s == 2.0
    assert len(result.trace.times) == 200


def test_print_is_recorded_with_simulated_time(run):
    result = run("""
        import time
        print("hello")
        time.sleep(2)
        print("after", round(time.time() - START if False else 0))
    """)
    lines = [(round(o.t_s, 3), o.text) for o in result.trace.output]
    assert lines[0] == (0.0, "hello")
    assert lines[1][0] >= 2.0


def test_clocks_follow_virtual_time(run):
    result = run("""
        import time
        t0, m0, p0 = time.time(), time.monotonic(), time.perf_counter()
        time.sleep(12.5)
        print(round(time.time() - t0, 3), round(time.monotonic() - m0, 3), round(time.perf_counter() - p0, 3))
    """)
    assert result.trace.output[0].text == "12.5 12.5 12.5"
    assert result.wall_time_s < 5


def test_sys_exit_ends_the_program_normally(run):
    result = run("""
        import sys
        print("bye")
        sys.exit(0)
        print("never")
    """)
    assert result.status == "finished"
    assert [o.text for o in result.trace.output] == ["bye"]


def test_outside_a_run_nothing_changes(run):
    import time

    before = (time.sleep, time.time, sys.stdout, sys.modules.get("ev3dev2"))
    run("import ev3dev2.motor\nprint('inside')")
    assert (time.sleep, time.time, sys.stdout, sys.modules.get("ev3dev2")) == before


def test_a_real_ev3dev2_installed_beside_is_not_shadowed(run, tmp_path, monkeypatch):
    for name in [m for m in sys.modules if m == "ev3dev2" or m.startswith("ev3dev2.")]:
        monkeypatch.delitem(sys.modules, name)
    real = tmp_path / "site" / "ev3dev2"
    real.mkdir(parents=True)
    (real / "__init__.py").write_text("REAL = True\n")
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    import ev3dev2

    assert ev3dev2.REAL
    result = run("""
        import ev3dev2
        print(hasattr(ev3dev2, "REAL"), hasattr(ev3dev2, "DeviceNotFound"))
    """)
    assert result.trace.output[0].text == "False True"
    assert sys.modules["ev3dev2"] is ev3dev2
    monkeypatch.delitem(sys.modules, "ev3dev2")


def test_odometry_thread_runs_in_virtual_time(run):
    result = run("""
        from ev3dev2.motor import MoveDifferential, OUTPUT_B, OUTPUT_C, SpeedRPM
        from ev3dev2.wheel import EV3EducationSetTire
        mdiff = MoveDifferential(OUTPUT_B, OUTPUT_C, EV3EducationSetTire, 120)
        mdiff.odometry_start(theta_degrees_start=0)
        mdiff.on_for_distance(SpeedRPM(40), 300)
        print(round(mdiff.x_pos_mm), round(mdiff.y_pos_mm))
        mdiff.odometry_stop()
    """)
    assert result.status == "finished", result.reason
    x_mm, y_mm = map(int, result.trace.output[-1].text.split())
    assert abs(x_mm - 300) < 10 and abs(y_mm) < 5


def test_two_programs_drive_two_robots_that_see_each_other(tmp_path):
    from ev3sim2d.simulator.run import run_programs

    world = arena(
        start="- {x_cm: 40, y_cm: 120, heading_deg: 0}\n  - {x_cm: 140, y_cm: 120, heading_deg: 180}"
    )
    watcher = tmp_path / "watcher.py"
    watcher.write_text(
        "from ev3dev2.sensor.lego import UltrasonicSensor\nprint(UltrasonicSensor().distance_centimeters)\n"
    )
    mover = tmp_path / "mover.py"
    mover.write_text(
        "from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C\n"
        "MoveTank(OUTPUT_B, OUTPUT_C).on_for_rotations(30, 30, 1)\n"
    )
    result = run_programs([watcher, mover], world, time_limit_s=10)
    assert result.status == "finished", result.reason
    # robot 2 faces robot 1: its front is 9 cm ahead of its centre at x=140; robot 1's sensor is at x=48
    assert abs(float(result.trace.output[0].text) - (140 - 9 - 48)) <= 0.2
    assert result.trace.output[0].robot == 0
    end2 = result.trace.poses(1)[-1]
    assert abs((140 - end2[0]) - WHEEL_CIRCUMFERENCE_CM) < 0.2


def test_logging_and_stderr_are_captured_and_logging_is_restored_after_the_run(run):
    import logging

    handlers_before = list(logging.root.handlers)
    result = run("""
        import logging, sys
        logging.basicConfig(level=logging.INFO, force=True)
        logging.getLogger("mine").info("from the program %d", 7)
        print("oops", file=sys.stderr)
    """)
    lines = [(o.stream, o.text) for o in result.trace.output]
    assert ("stderr", "INFO:mine:from the program 7") in lines
    assert ("stderr", "oops") in lines
    assert logging.root.handlers == handlers_before


def test_sleep_from_ev3dev2_auto_is_virtual(run):
    result = run("""
        from ev3dev2.auto import *
        sleep(2)
        print("slept")
    """)
    assert result.sim_time_s >= 2.0
    assert result.wall_time_s < 1.0


def test_datetime_now_follows_the_virtual_clock(run):
    import datetime

    result = run("""
        import time
        from datetime import datetime, date
        time.sleep(3)
        print(datetime.now().isoformat(), date.today().isoformat())
    """)
    assert result.trace.output[0].text == "2025-01-01T00:00:03 2025-01-01"
    assert datetime.datetime.now().year >= 2026  # outside the run, the real clock


def test_a_line_with_a_lone_surrogate_as_a_file_name_may_hold_is_printed_not_a_protocol_breach(run):
    """os.listdir gives a file name that is not UTF-8 as text with a lone surrogate; printing it is
    honest, and must not end the brick (its message went as surrogatepass and came back strict)."""
    result = run('print("a\\udce9b")\n')
    assert result.status == "finished", result.reason
    assert result.trace.output[0].text == "a\udce9b"
