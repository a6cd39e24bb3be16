"""The trace: what a run recorded, saved and loaded back unchanged."""

from ev3sim2d.trace import Trace


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
    state = motion[:, 4 + 3 * ports.index("outB") + 2]
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
