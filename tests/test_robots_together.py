"""Several robots in one world (issue 13): they push each other, see each other and hear each other.

Each test runs real programs, one per robot, through run_programs in a walled arena (inside x, y
in [12, 228] cm) with two starts.  The driving base's body reaches 9 cm ahead of its centre and
7 cm behind it, and is 15 cm wide; its ultrasonic sensor sits 8 cm ahead of the centre.
The push model (physics.py, docs/simulation.md): a robot's push is the sum of its wheel motors'
power in % (a regulated run: speed_sp as a share of max_speed); a stopped robot's wheels hold with
HOLD_PCT (hold), BRAKE_PCT (brake) or COAST_PCT (coast) each.
"""

from __future__ import annotations

import textwrap

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.robot_spec import load_robot
from tests.inline_world import arena, two_wheel_robot

HEAD_ON = "- {x_cm: 80, y_cm: 120, heading_deg: 0}\n  - {x_cm: 110, y_cm: 120, heading_deg: 180}"


def _programs(tmp_path, *sources: str) -> list:
    paths = []
    for i, source in enumerate(sources):
        path = tmp_path / f"robot{i + 1}.py"
        path.write_text(textwrap.dedent(source))
        paths.append(path)
    return paths


def _run(tmp_path, world, *sources: str, **options):
    result = run_programs(_programs(tmp_path, *sources), world, time_limit_s=20, hang_after_s=5.0, **options)
    assert result.status == "finished", result.reason
    return result


def _lines(result, robot: int) -> list[str]:
    return [o.text for o in result.trace.output if o.robot == robot]


def _drive(speed: int, seconds: float) -> str:
    """A program driving straight ahead at speed % for seconds, then saying where its wheels are
    and whether they ever stalled."""
    return f"""
        import time
        from ev3dev2.motor import LargeMotor, MoveTank, OUTPUT_B, OUTPUT_C
        tank, left = MoveTank(OUTPUT_B, OUTPUT_C), LargeMotor(OUTPUT_B)
        tank.on({speed}, {speed})
        stalled = False
        for _ in range(int({seconds} / 0.05)):
            time.sleep(0.05)
            stalled = stalled or "stalled" in left.state
        print(left.position, stalled, " ".join(left.state))
        tank.off(brake=True)
    """


def _stand(stop: str, seconds: float = 3.0) -> str:
    """A program that stops its wheels with stop action `stop` and waits, then says where they are."""
    return f"""
        import time
        from ev3dev2.motor import LargeMotor, OUTPUT_B, OUTPUT_C
        for port in (OUTPUT_B, OUTPUT_C):
            motor = LargeMotor(port)
            motor.stop_action = "{stop}"
            motor.stop()
        time.sleep({seconds})
        print(LargeMotor(OUTPUT_B).position)
    """


def test_a_faster_robot_pushes_a_slower_one_back(tmp_path):
    # robot 1 at 60 % drives +x into robot 2 driving -x at 20 %: 1 wins and 2 goes backwards
    result = _run(tmp_path, arena(start=HEAD_ON), _drive(60, 3.0), _drive(20, 3.0))
    first, second = result.trace.poses(0), result.trace.poses(1)
    assert first[-1][0] > 80 + 20, "the pusher went on"
    assert second[-1][0] > 110 + 20, "the pushed robot moved the way it was pushed, +x"
    assert abs(second[-1][1] - 120) < 1 and abs(first[-1][1] - 120) < 1
    position, stalled, _ = _lines(result, 1)[0].split(" ", 2)
    assert int(position) < -200, "its encoders counted its wheels turning backwards"
    assert stalled == "True", "driving forward while pushed back, its motors reported stalled"
    position, stalled, _ = _lines(result, 0)[0].split(" ", 2)
    assert int(position) > 300 and stalled == "False"


def test_equal_robots_head_on_stall_each_other(tmp_path):
    result = _run(tmp_path, arena(start=HEAD_ON), _drive(40, 2.0), _drive(40, 2.0))
    first, second = result.trace.poses(0), result.trace.poses(1)
    # they meet halfway (their fronts touch at x = 95) and stay there
    assert abs(first[-1][0] - (95 - 9)) < 0.5
    assert abs(second[-1][0] - (95 + 9)) < 0.5
    for robot in (0, 1):
        position, stalled, state = _lines(result, robot)[0].split(" ", 2)
        assert stalled == "True" and "stalled" in state
        # each wheel turned only the 6 cm to the meeting point (56 mm wheels: 17.6 cm a turn)
        assert abs(int(position) - 6 / 17.59 * 360) < 10


@pytest.mark.parametrize(
    "speed, stop, moves",
    [
        (40, "brake", False),  # 2 x 40 % = 80 % against 2 x 50 %: the brakes hold
        (95, "brake", True),  # 190 % > 100 %
        (95, "hold", False),  # 190 % < 2 x 100 %
        (20, "coast", True),  # 40 % > 2 x 5 %
    ],
)
def test_a_standing_robot_is_moved_only_by_a_push_stronger_than_its_wheels_hold(tmp_path, speed, stop, moves):
    result = _run(tmp_path, arena(start=HEAD_ON), _drive(speed, 2.5), _stand(stop, 3.0))
    second = result.trace.poses(1)
    moved = second[-1][0] - 110
    position = int(_lines(result, 1)[0])
    if moves:
        assert moved > 5, f"robot 2 moved {moved:.2f} cm"
        assert position < -20, "its wheels turned backwards as it was pushed"
    else:
        assert abs(moved) < 0.5, f"robot 2 moved {moved:.2f} cm"
        assert abs(position) <= 3
        assert _lines(result, 0)[0].split(" ", 2)[1] == "True", "the pusher stalled"


def test_the_ultrasonic_and_infrared_sensors_see_the_other_robot_not_the_wall_behind(tmp_path):
    # robot 2 stands across robot 1's path: its side is at x = 100 - 7.5; the wall is at x = 228
    world = arena(
        start="- {x_cm: 40, y_cm: 120, heading_deg: 0}\n  - {x_cm: 100, y_cm: 120, heading_deg: 90}"
    )
    watcher = """
        from ev3dev2.sensor.lego import UltrasonicSensor
        print(UltrasonicSensor().distance_centimeters)
    """
    result = _run(tmp_path, world, watcher, "import time\ntime.sleep(0.5)\n")
    assert abs(float(_lines(result, 0)[0]) - (100 - 7.5 - 48)) <= 0.3

    robot = tmp_path / "ir.yaml"
    robot.write_text(
        open(world.robot.source)
        .read()
        .replace("kind: ultrasonic", "kind: infrared")
        .replace("cone_deg: 15", "cone_deg: 30")
    )
    watcher = """
        from ev3dev2.sensor.lego import InfraredSensor
        print(InfraredSensor().proximity)
    """
    result = _run(tmp_path, world, watcher, "import time\ntime.sleep(0.5)\n", robot=load_robot(robot))
    # 44.5 cm away, proximity 100 at 70 cm: about 64; with only the wall 180 cm away it reads 100
    assert 55 <= int(_lines(result, 0)[0]) <= 70


def test_a_touch_bumper_is_pressed_by_the_other_robot(tmp_path):
    world = arena(
        start="- {x_cm: 40, y_cm: 120, heading_deg: 0}\n  - {x_cm: 100, y_cm: 120, heading_deg: 90}"
    )
    driver = """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        from ev3dev2.sensor.lego import TouchSensor
        touch, tank = TouchSensor(), MoveTank(OUTPUT_B, OUTPUT_C)
        tank.on(20, 20)
        touch.wait_for_pressed()
        tank.off()
        print("pressed")
    """
    result = _run(tmp_path, world, driver, "import time\ntime.sleep(6)\n")
    assert _lines(result, 0) == ["pressed"]
    # its front (9 cm ahead) stopped at robot 2's side, x = 92.5, not at the wall at 228
    assert abs(result.trace.poses(0)[-1][0] + 9 - 92.5) < 1.5


SOUND_ROBOT = two_wheel_robot("listener", "{port: 2, kind: nxt-sound, angle_deg: 180, radius_cm: 3}")

LISTENER = """
    import time
    from ev3dev2.sensor.lego import SoundSensor
    mic = SoundSensor()
    print(mic.sound_pressure)
    time.sleep(1.0)
    print(mic.sound_pressure)
"""


def _beeper(volume: int) -> str:
    return f"""
        import time
        from ev3dev2.sound import Sound
        time.sleep(0.5)
        Sound().play_tone(440, 1.5, volume={volume})
    """


@pytest.mark.parametrize(
    "distance_cm, volume, heard",
    [
        (20, 100, 5 + 60 * (10 / 20) ** 2),  # 20.0 %
        (100, 100, 5 + 60 * (10 / 100) ** 2),  # 5.6 %
        (20, 50, 5 + 30 * (10 / 20) ** 2),  # 12.5 %
    ],
)
def test_the_sound_sensor_hears_another_robot_louder_from_near(tmp_path, distance_cm, volume, heard):
    robot = tmp_path / "listener.yaml"
    robot.write_text(SOUND_ROBOT)
    # the listener's sensor is 3 cm behind its centre at x = 40; the beeper's speaker at its centre
    world = arena(
        start=f"- {{x_cm: 40, y_cm: 120, heading_deg: 0}}\n  - {{x_cm: {37 + distance_cm}, y_cm: 120, heading_deg: 0}}"
    )
    result = _run(tmp_path, world, LISTENER, _beeper(volume), robot=load_robot(robot))
    before, during = (float(v) for v in _lines(result, 0))
    assert before == 5.0, "the quiet room before the beeper plays"
    assert during == pytest.approx(heard, abs=0.1)


def test_a_beep_from_20_cm_is_louder_than_from_a_metre(tmp_path):
    robot = tmp_path / "listener.yaml"
    robot.write_text(SOUND_ROBOT)
    heard = {}
    for distance_cm in (20, 100):
        world = arena(
            start=f"- {{x_cm: 40, y_cm: 120, heading_deg: 0}}\n  - {{x_cm: {37 + distance_cm}, y_cm: 120, heading_deg: 0}}"
        )
        beeper = "import time\nfrom ev3dev2.sound import Sound\ntime.sleep(0.5)\nSound().beep('-l 1500')\n"
        result = _run(tmp_path, world, LISTENER, beeper, robot=load_robot(robot))
        heard[distance_cm] = float(_lines(result, 0)[1])
    assert heard[20] > heard[100] > 5.0


def test_a_robot_whose_program_ends_stops_while_the_others_run_on(tmp_path):
    # as brickman does on an EV3: a program's end resets its motors, whatever it left them doing; a reset
    # coasts a turning motor to a stop (legoev3_motor_reset), so the robot rolls out a little, then stays
    leaves_running = """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C
        MoveTank(OUTPUT_B, OUTPUT_C).on(50, 50)
    """
    waits = """
        import time
        time.sleep(3)
    """
    far_apart = "- {x_cm: 60, y_cm: 60, heading_deg: 0}\n  - {x_cm: 60, y_cm: 180, heading_deg: 0}"
    result = _run(tmp_path, arena(start=far_apart), leaves_running, waits)
    assert result.sim_time_s == pytest.approx(3.0, abs=0.02)
    poses = result.trace.poses(0)
    moved = poses[-1][0] - 60
    assert moved < 5.0, f"the robot drove on {moved:.1f} cm after its program ended"
    assert poses[100][0] == pytest.approx(poses[-1][0], abs=0.01), "it rolled on for more than a second"
    assert result.trace.end_motors[0]["driving"] is True  # what the program left its motors doing
    assert [r["status"] for r in result.robots] == ["finished", "finished"]
