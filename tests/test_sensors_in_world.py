"""Sensors read the world: colour under the spot, distance ahead, bumper, noise."""

from ev3sim2d.simulator.simulation import Simulation
from tests.inline_world import arena, two_wheel_robot

# a 12 cm grid with one black column (col 5: x 60..72) on white floor
STRIPE = ["#" + "...." + "k" + "." * 13 + "#"] * 18


def color_world(x_cm):
    return arena(inner=STRIPE, start=f"x_cm: {x_cm}\n  y_cm: 120\n  heading_deg: 0")


def read(world, port, mode=None, seed=0):
    sim = Simulation(world, [("robot", world.robot, world.start)], seed=seed)
    sensor = sim.robots[0].sensors[port]
    if mode:
        sensor.write("mode", mode)
    return sensor.values()


def test_reflected_light_is_dark_on_the_line_and_light_beside_it():
    # the colour sensor sits 7 cm ahead of the robot centre
    on_line = read(color_world(66 - 7), "in3")[0]
    on_floor = read(color_world(40 - 7), "in3")[0]
    assert on_line == 5
    assert on_floor == 75


def test_reflected_light_changes_smoothly_across_the_edge():
    values = [read(color_world(60 + dx / 10 - 7), "in3")[0] for dx in range(-10, 11)]
    assert values[0] == 75 and values[-1] == 5
    assert all(a >= b for a, b in zip(values, values[1:], strict=False))
    assert len(set(values)) >= 8  # many steps between, not a jump
    middle = values[10]
    assert 35 <= middle <= 45


def test_colour_mode_names_the_colour_under_the_spot():
    assert read(color_world(66 - 7), "in3", "COL-COLOR") == (1,)  # black
    assert read(color_world(40 - 7), "in3", "COL-COLOR") == (6,)  # white


def test_ultrasonic_measures_the_distance_to_the_wall_ahead():
    world = arena(start="x_cm: 100\n  y_cm: 120\n  heading_deg: 0")
    (value,) = read(world, "in4")
    # sensor 8 cm ahead of the centre; wall face at 228 cm; value in tenths of cm
    assert value == (228 - 108) * 10


def test_ultrasonic_reads_255_cm_when_nothing_is_in_range():
    world = arena(width=40, height=20, start="x_cm: 30\n  y_cm: 120\n  heading_deg: 0")
    assert read(world, "in4") == (2550,)


def test_touch_sensor_is_pressed_only_against_a_wall():
    free = arena(start="x_cm: 100\n  y_cm: 120\n  heading_deg: 0")
    at_wall = arena(start="x_cm: 218.8\n  y_cm: 120\n  heading_deg: 0")  # bumper 9 cm ahead, wall at 228
    assert read(free, "in1") == (0,)
    assert read(at_wall, "in1") == (1,)


def test_gyro_reads_zero_at_the_start_whatever_the_heading():
    world = arena(start="x_cm: 100\n  y_cm: 120\n  heading_deg: 135")
    assert read(world, "in2") == (0,)


def test_noise_is_reproducible_with_the_same_seed_and_differs_with_another(tmp_path):
    robot = tmp_path / "noisy.yaml"
    from ev3sim2d.world.robot_spec import default_robot

    source = open(default_robot().source).read().replace("spot_cm: 1.5}", "spot_cm: 1.5, noise: 3}")
    robot.write_text(source)
    world = arena(inner=STRIPE, start="x_cm: 33\n  y_cm: 120\n  heading_deg: 0", extra=f"robot: {robot}\n")

    def samples(seed):
        sim = Simulation(world, [("robot", world.robot, world.start)], seed=seed)
        sensor = sim.robots[0].sensors["in3"]
        out = []
        for tick in range(1, 40):
            sim.tick(tick * sim.tick_us)
            out.append(sensor.values()[0])
        return out

    a, b, c = samples(1), samples(1), samples(2)
    assert a == b
    assert a != c
    assert len(set(a)) > 3
    assert 70 <= sum(a) / len(a) <= 80


NXT_ROBOT = two_wheel_robot(
    "NXT sensors",
    "{port: 1, kind: nxt-light, angle_deg: 0, radius_cm: 7}",
    "{port: 2, kind: nxt-sound, angle_deg: 180, radius_cm: 3}",
)


def test_nxt_light_and_sound_sensors_work_where_the_robot_has_them(run, tmp_path):
    from ev3sim2d.world.robot_spec import load_robot

    robot_file = tmp_path / "nxt.yaml"
    robot_file.write_text(NXT_ROBOT)
    result = run(
        """
        import time
        from ev3dev2.sensor.lego import LightSensor, SoundSensor
        from ev3dev2.sound import Sound
        light, mic = LightSensor(), SoundSensor()
        print(light.reflected_light_intensity, mic.sound_pressure)
        Sound().play_tone(440, 1.0, play_type=Sound.PLAY_NO_WAIT_FOR_COMPLETE)
        time.sleep(0.1)
        print(mic.sound_pressure)
        """,
        color_world(66 - 7),
        robot=load_robot(robot_file),
    )
    assert result.status == "finished", result.reason
    lines = [o.text for o in result.trace.output]
    assert lines[0] == f"{(20 + 0.55 * 5):.1f} 5.0"  # on the black line; a quiet room
    assert lines[1] == "60.0"  # its own speaker


def test_noise_leaves_values_that_name_something_alone(tmp_path):
    from ev3sim2d.world.robot_spec import default_robot

    source = open(default_robot().source).read().replace("spot_cm: 1.5}", "spot_cm: 1.5, noise: 20}")
    robot = tmp_path / "noisy.yaml"
    robot.write_text(source)
    world = arena(inner=STRIPE, start="x_cm: 59\n  y_cm: 120\n  heading_deg: 0", extra=f"robot: {robot}\n")
    sim = Simulation(world, [("robot", world.robot, world.start)], seed=3)
    sensor = sim.robots[0].sensors["in3"]
    sensor.write("mode", "COL-COLOR")
    colours = set()
    for tick in range(1, 30):
        sim.tick(tick * sim.tick_us)
        colours.add(sensor.values()[0])
    assert colours == {1}  # black, every time
