"""The trace: what a run recorded, saved and loaded back unchanged."""

from ev3sim2d.results.trace import POSE_COLUMNS, Trace


def test_a_saved_trace_loads_back_with_the_same_fingerprint(run, tmp_path):
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import ColorSensor
        eye = ColorSensor()
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 1)
        print(eye.reflected_light_intensity)
    """)
    path = tmp_path / "run.npz"
    result.trace.save(path)
    loaded = Trace.load(path)
    assert loaded.fingerprint() == result.trace.fingerprint()
    assert (loaded.motion() == result.trace.motion()).all()
    assert loaded.output[0].text == result.trace.output[0].text
    assert loaded.result["status"] == "finished"


def test_every_tick_is_recorded_with_poses_and_motor_states(run):
    result = run("""
        from ev3dev2.motor import LargeMotor, OUTPUT_B
        LargeMotor(OUTPUT_B).on_for_seconds(50, 0.5)
    """)
    trace = result.trace
    assert len(trace.times) == round(result.sim_time_s / trace.tick_s)
    motion = trace.motion()
    assert motion.shape == (len(trace.times), trace.width)
    ports = [port for port, _ in trace.robots[0]["motors"]]
    state = motion[:, len(POSE_COLUMNS) + 3 * ports.index("outB") + 2]
    assert (state == 1).sum() > 40  # running (and nothing else) for most of the half second
    assert state[-1] == 4  # holding at the end (brake=True)


def test_sensor_values_the_program_read_are_in_the_trace(run):
    result = run("""
        from ev3dev2.sensor.lego import UltrasonicSensor
        import time
        us = UltrasonicSensor()
        time.sleep(0.05)
        print(us.value())
    """)
    read = int(result.trace.output[0].text)
    samples = [s for s in result.trace.sensor_samples if s[2] == "in4"]
    assert [read] in [s[4] for s in samples]
    assert all(s[3] == "US-DIST-CM" for s in samples)


def test_a_different_seed_or_program_changes_the_fingerprint(run):
    a = run("import time\ntime.sleep(0.5)\nprint(1)")
    b = run("import time\ntime.sleep(0.5)\nprint(2)")
    assert a.trace.fingerprint() != b.trace.fingerprint()


def test_sounds_and_leds_are_recorded_as_events(run, tmp_path):
    result = run("""
        from ev3dev2.sound import Sound
        from ev3dev2.led import Leds
        Sound().beep()
        Leds().set_color("LEFT", "RED")
        Sound().speak("hello")
    """)
    assert result.status == "finished", result.reason
    kinds = [(e[2], e[3].get("kind")) for e in result.trace.events]
    assert ("sound", "beep") in kinds and ("sound", "speak") in kinds
    leds = [e for e in result.trace.events if e[2] == "leds"]
    assert leds[-1][3]["led0:red:brick-status"] == 255 and leds[-1][3]["led0:green:brick-status"] == 0
    beep_t = next(e[0] for e in result.trace.events if e[3].get("kind") == "beep")
    led_t = leds[0][0]
    assert led_t >= beep_t + 0.2  # the program waited for the 200 ms beep
    path = tmp_path / "t.npz"
    result.trace.save(path)
    assert Trace.load(path).events == result.trace.events


def test_the_motors_state_at_the_end_is_kept_even_after_the_last_tick(run):
    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        import time
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(30, 30)
        time.sleep(0.5)
        tank.off()  # after the last tick of the run: only end_motors sees it
    """)
    assert result.trace.end_motors == [
        {"driving": False, "states": {"outA": "", "outB": "holding", "outC": "holding"}}
    ]
    running = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        MoveTank(OUTPUT_B, OUTPUT_C).on(30, 30)
    """)
    assert running.trace.end_motors[0]["driving"] is True


TWO_ROBOTS = "- {x_cm: 60, y_cm: 120, heading_deg: 0}\n  - {x_cm: 120, y_cm: 120, heading_deg: 0}"
DRIVE = """
from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(50, 50, {seconds})
"""


def _two_robots(tmp_path, first_drives_s: float):
    from ev3sim2d.simulator.run import run_programs
    from tests.inline_world import arena

    paths = [tmp_path / "behind.py", tmp_path / "ahead.py"]
    paths[0].write_text(DRIVE.format(seconds=first_drives_s))
    paths[1].write_text("import time\ntime.sleep(3)\n")
    return run_programs(paths, arena(start=TWO_ROBOTS), time_limit_s=10, hang_after_s=5.0)


def _column(trace: Trace, robot: int, name: str):
    return trace.motion()[:, trace.robot_columns(robot)][:, POSE_COLUMNS.index(name)]


def test_a_robot_touching_another_is_recorded_for_both_and_not_as_a_wall(tmp_path):
    result = _two_robots(tmp_path, first_drives_s=3)  # 60 cm apart, 16 cm of bodies: it runs into the other
    trace = result.trace
    for robot in (0, 1):
        assert _column(trace, robot, "touching_robot").any()
        assert not _column(trace, robot, "touching").any()
    first = trace.times[int(_column(trace, 0, "touching_robot").argmax())]
    assert 1.0 < first < 3.0  # (60 - 16) cm at about 26 cm/s


def test_robots_that_keep_apart_never_touch(tmp_path):
    result = _two_robots(tmp_path, first_drives_s=0.5)
    assert not _column(result.trace, 0, "touching_robot").any()


def test_a_trace_saved_before_robot_contacts_were_recorded_still_loads(run, tmp_path):
    import json

    import numpy as np

    result = run("""
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds(30, 30, 0.5)
    """)
    path = tmp_path / "new.npz"
    result.trace.save(path)
    old = tmp_path / "old.npz"
    with np.load(path) as data:  # the same file as an older ev3sim2d wrote it: no touching_robot column
        parts = dict(data)
    column = POSE_COLUMNS.index("touching_robot")
    parts["motion"] = np.delete(parts["motion"], column, axis=1)
    json.loads(bytes(parts["meta"]).decode())  # (the meta is unchanged)
    np.savez_compressed(old, **parts)
    loaded = Trace.load(old)
    assert (loaded.motion() == result.trace.motion()).all()
    assert loaded.fingerprint() == result.trace.fingerprint()
