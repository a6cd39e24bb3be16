"""Every program in examples/ runs as shipped and does in the world what its docstring says."""

import math
from pathlib import Path

import pytest

from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.button_press import parse_press
from ev3sim2d.world.maze_file import find_maze, load_maze
from ev3sim2d.world.robot_spec import load_robot

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run_example(name, maze="empty", **options):
    options.setdefault("time_limit_s", 60)
    world = load_maze(find_maze(maze))
    result = run_programs([EXAMPLES / f"{name}.py"], world, hang_after_s=10, **options)
    assert result.status == "finished", result.reason
    return result, world


def printed(result):
    return [o.text for o in result.trace.output]


def end_pose(result):
    return result.trace.poses(0)[-1]


def test_every_example_is_tested():
    tested = {name[len("test_") :] for name in globals() if name.startswith("test_")}
    for path in EXAMPLES.glob("*.py"):
        assert path.stem in tested or path.stem == "line_follower", f"examples/{path.name} has no test"


def test_line_follower():
    world = load_maze(find_maze("line"))
    result = run_programs([EXAMPLES / "line_follower.py"], world, time_limit_s=30)
    assert result.status == "time_limit"
    assert result.trace.robots and sum(1 for _ in result.trace.times) == 3000
    assert world.regions["start"].contains(*result.trace.poses(0)[0][:2])


def test_drive_square():
    result, world = run_example("drive_square")
    x, y, heading = end_pose(result)
    assert math.hypot(x - world.start.x_cm, y - world.start.y_cm) < 3
    assert abs(((heading - world.start.heading_deg) + 180) % 360 - 180) < 4
    assert printed(result) == [f"side {i} done" for i in range(1, 5)]


def test_motor_low_level():
    result, _ = run_example("motor_low_level")
    lines = printed(result)
    assert lines[0] == "driver lego-ev3-m-motor max speed 1560 counts per rotation 360"
    assert lines[1] == "after run_to_rel_pos: 180 ['holding']"
    assert lines[3] == "after reset: 0 0 coast"


def test_color_sensor():
    result, world = run_example("color_sensor", "colors")
    assert printed(result)[-1].startswith("Red")
    x, y, heading = end_pose(result)
    h = math.radians(heading)
    eye = (x + 7 * math.cos(h), y + 7 * math.sin(h))
    assert world.regions["red"].contains(*eye)


def test_ultrasonic_sensor():
    result, world = run_example("ultrasonic_sensor")
    distance = float(printed(result)[-1].split()[2])
    assert 19 <= distance <= 20.5
    x = end_pose(result)[0]
    wall = (world.grid.width - 1) * world.grid.cell_cm
    assert abs(wall - (x + 8) - distance) < 0.5


def test_touch_sensor():
    result, world = run_example("touch_sensor")
    assert printed(result)[0] == "bump!"
    wall = (world.grid.width - 1) * world.grid.cell_cm
    x, _, heading = end_pose(result)
    assert x < wall - 9 - 8  # backed off
    assert 150 < abs(heading - world.start.heading_deg) < 190  # turned round


def test_gyro_sensor():
    result, world = run_example("gyro_sensor")
    angle = int(printed(result)[0].split()[1])
    assert 90 <= angle <= 93
    assert abs(end_pose(result)[2] - (world.start.heading_deg - angle)) < 1.5


def test_infrared_sensor():
    robot = load_robot(EXAMPLES / "robots" / "ir-base.yaml")
    result, world = run_example("infrared_sensor", robot=robot)
    proximity = int(printed(result)[0].split()[1])
    assert 26 <= proximity < 30
    wall = (world.grid.width - 1) * world.grid.cell_cm
    assert abs(wall - (end_pose(result)[0] + 8) - 0.7 * proximity) < 2


def test_sound():
    result, _ = run_example("sound")
    sounds = [e[3] for e in result.trace.events if e[2] == "sound" and e[3]["kind"] != "set_volume"]
    assert [s["kind"] for s in sounds] == ["beep", "beep", "beep", "speak"]  # beep, tones, note, speech
    assert sounds[3]["text"] == "Hello from the simulator"
    assert result.sim_time_s > 0.2 + 3 * 0.45 + 0.5  # it waited for each sound to end


def test_leds():
    result, _ = run_example("leds")
    states = [e[3] for e in result.trace.events if e[2] == "leds"]
    red_left = [s["led0:red:brick-status"] for s in states]
    green_left = [s["led0:green:brick-status"] for s in states]
    assert 255 in red_left and 255 in green_left
    assert states[-1] == dict.fromkeys(states[-1], 0)  # all off at the end
    assert result.trace.poses(0)[-1][0] > result.trace.poses(0)[0][0] + 5  # it drove


def test_buttons():
    presses = [parse_press("enter@1.0"), parse_press("down@4.0")]
    result, _ = run_example("buttons", presses=presses)
    times = {o.text: o.t_s for o in result.trace.output}
    assert 1.2 <= times["go"] < 1.3
    assert 4.0 <= times["stopped by Down"] < 4.1
    moved = result.trace.poses(0)[-1][0] - result.trace.poses(0)[0][0]
    assert moved > 20


def test_display():
    result, _ = run_example("display")
    frames = [e for e in result.trace.events if e[2] == "lcd"]
    assert len(frames) == 3
    pixels = result.trace.lcd_frames[frames[-1][3]["frame"]]
    assert len(pixels) == 178 * 128
    assert pixels.count(0) > 500 and pixels.count(255) > 10000  # black drawing on a white screen


def test_odometry():
    result, world = run_example("odometry")
    x, y, _ = end_pose(result)
    assert math.hypot(x - world.start.x_cm, y - world.start.y_cm) < 2
    assert printed(result)[-1].startswith("at ")


def test_threads():
    result, _ = run_example("threads")
    assert printed(result)[0].startswith("bumped into the wall after")
    left_green = [e[3]["led0:green:brick-status"] for e in result.trace.events if e[2] == "leds"]
    assert left_green.count(255) >= 3  # it blinked while driving
    final = [e[3] for e in result.trace.events if e[2] == "leds"][-1]
    assert final["led0:red:brick-status"] == 255


def test_sumo(tmp_path):
    # against a robot that only stands there (coasting), in the ring of mazes/sumo.yaml
    standing = tmp_path / "standing.py"
    standing.write_text("import time\ntime.sleep(60)\n")
    world = load_maze(find_maze("sumo"))
    result = run_programs([EXAMPLES / "sumo.py", standing], world, time_limit_s=20, hang_after_s=10)
    assert result.status == "time_limit", result.reason
    fighter, pushed = result.trace.poses(0)[-1], result.trace.poses(1)[-1]
    assert pushed[0] > 160, "the standing robot was pushed onto the ring's edge (it started at x 122)"
    assert world.regions["ring"].contains(*fighter[:2]), "the fighter stayed in the ring"


@pytest.mark.parametrize("name", ["drive_square", "odometry", "threads"])
def test_examples_are_deterministic(name):
    a, _ = run_example(name)
    b, _ = run_example(name)
    assert a.trace.fingerprint() == b.trace.fingerprint()


def test_console_text_is_drawn_on_the_lcd(tmp_path):
    program = tmp_path / "console.py"
    program.write_text(
        "from ev3dev2.console import Console\n"
        "c = Console()\n"
        "c.text_at('Hello', column=2, row=2)\n"
        "c.text_at('World', column=2, row=3)\n"
    )
    world = load_maze(find_maze("empty"))
    result = run_programs([program], world, time_limit_s=5)
    assert result.status == "finished", result.reason
    frames = [e[3]["frame"] for e in result.trace.events if e[2] == "lcd"]
    assert len(frames) >= 2
    last = result.trace.lcd_frames[frames[-1]]
    assert sum(1 for p in last if p < 128) > 50  # dark text pixels on the white screen


# -- examples/pybricks: the same kind of programs in Pybricks 2.0 (LEGO's EV3 MicroPython) -------------

PYBRICKS = EXAMPLES / "pybricks"
PYBRICKS_TOGETHER = {"messaging_server": "messaging", "messaging_client": "messaging"}  # one test, one run


def run_pybricks(name, maze="empty", **options):
    return run_example(f"pybricks/{name}", maze, **options)


def test_every_pybricks_example_is_tested():
    tested = {name[len("test_pybricks_") :] for name in globals() if name.startswith("test_pybricks_")}
    for path in PYBRICKS.glob("*.py"):
        assert PYBRICKS_TOGETHER.get(path.stem, path.stem) in tested, (
            f"examples/pybricks/{path.name} has no test"
        )
        assert path.read_text().startswith("#!/usr/bin/env pybricks-micropython\n"), path.name


def test_pybricks_line_follower():
    """robotics.drive (extmod/modrobotics.c: robotics_DriveBase_drive) steered by reflection()."""
    world = load_maze(find_maze("line"))
    result = run_programs([PYBRICKS / "line_follower.py"], world, time_limit_s=30)
    assert result.status == "time_limit", result.reason
    poses = result.trace.poses(0)
    assert world.regions["start"].contains(*poses[0][:2])
    travelled = sum(math.dist(a[:2], b[:2]) for a, b in zip(poses[:-1], poses[1:], strict=True))
    assert travelled > 300  # 150 mm/s for 30 s, round the line's bends


def test_pybricks_drive_square():
    """DriveBase.straight and turn (extmod/modrobotics.c: robotics_DriveBase_straight, _turn): a positive
    angle turns clockwise, so four sides of 400 mm with turn(-90) end where they began."""
    result, world = run_pybricks("drive_square")
    poses = result.trace.poses(0)
    x, y, heading = poses[-1]
    assert math.hypot(x - world.start.x_cm, y - world.start.y_cm) < 2
    assert abs(((heading - world.start.heading_deg) + 180) % 360 - 180) < 3
    farthest = max(math.hypot(p[0] - world.start.x_cm, p[1] - world.start.y_cm) for p in poses)
    assert 55 < farthest < 58  # the far corner, 40 cm ahead and 40 cm to the left (56.6 cm)
    assert printed(result) == [
        *(f"side {i} done" for i in range(1, 5)),
        "driven 1600 mm, turned -360 degrees",
    ]


def test_pybricks_motor():
    """Motor.run_angle, run_target, run_time, reset_angle (extmod/modmotor.c); a motor made with
    Direction.COUNTERCLOCKWISE counts its own way round (motor_Motor_make_new)."""
    result, _ = run_pybricks("motor")
    lines = printed(result)
    assert lines[:3] == ["start 0", "after run_angle 180", "after run_target 0"]
    run_time = int(lines[3].split()[-1])
    assert -400 <= run_time <= -330  # 400 deg/s for 1 s, less the time to speed up
    assert lines[4:] == ["after reset_angle 0", "wheel 360"]
    start, end = result.trace.poses(0)[0], end_pose(result)
    assert end[0] < start[0] - 3  # the left wheel rolled a turn backwards: a pivot on the right wheel
    assert 60 < abs(end[2] - start[2]) < 100  # 17.6 cm of wheel round a 12 cm axle: about 84 degrees


def test_pybricks_touch_sensor():
    """TouchSensor.pressed (extmod/modev3devices.c: ev3devices_TouchSensor_pressed)."""
    result, world = run_pybricks("touch_sensor")
    assert printed(result) == ["bump!", "pressed now? False"]
    wall = (world.grid.width - 1) * world.grid.cell_cm
    x, _, heading = end_pose(result)
    assert x < wall - 9 - 8  # backed off
    assert 170 < abs(heading - world.start.heading_deg) < 190  # turned round


def test_pybricks_color_sensor():
    """ColorSensor.color (extmod/modev3devices.c: ev3devices_ColorSensor_color) names each patch."""
    result, world = run_pybricks("color_sensor", "colors")
    colors = printed(result)[1:]
    assert colors[-1] == "Color.RED"
    assert {"Color.BLUE", "Color.GREEN", "Color.YELLOW"} <= set(colors)
    x, y, heading = end_pose(result)
    h = math.radians(heading)
    assert world.regions["red"].contains(x + 7 * math.cos(h), y + 7 * math.sin(h))


def test_pybricks_ultrasonic_sensor():
    """UltrasonicSensor.distance in mm (extmod/modev3devices.c: ev3devices_UltrasonicSensor_distance)."""
    result, world = run_pybricks("ultrasonic_sensor")
    distance_mm = int(printed(result)[-1].split()[2])
    assert 190 <= distance_mm <= 205
    wall = (world.grid.width - 1) * world.grid.cell_cm
    assert abs(wall - (end_pose(result)[0] + 8) - distance_mm / 10) < 1


def test_pybricks_gyro_sensor():
    """GyroSensor.angle counts clockwise as positive (extmod/modev3devices.c: ev3devices_GyroSensor_angle)."""
    result, world = run_pybricks("gyro_sensor")
    turned = int(printed(result)[0].split()[1])
    assert 90 <= turned <= 93
    assert abs(end_pose(result)[2] - (world.start.heading_deg + turned)) < 2  # left: counter-clockwise


def test_pybricks_infrared_sensor():
    """InfraredSensor.distance, a relative 0 to 100 (extmod/modev3devices.c: _InfraredSensor_distance)."""
    robot = load_robot(EXAMPLES / "robots" / "ir-base.yaml")
    result, world = run_pybricks("infrared_sensor", robot=robot)
    proximity = int(printed(result)[0].split()[1])
    assert 20 <= proximity <= 25
    wall = (world.grid.width - 1) * world.grid.cell_cm
    assert abs(wall - (end_pose(result)[0] + 8) - 0.7 * proximity) < 2


def test_pybricks_buttons():
    """EV3Brick.buttons.pressed lists the buttons held (extmod/modbuttons.c: buttons_pressed)."""
    result, _ = run_pybricks("buttons", presses=[parse_press("enter@1.0"), parse_press("down@4.0")])
    times = {o.text: o.t_s for o in result.trace.output}
    assert 1.0 <= times["go"] < 1.1
    assert 4.0 <= times["stopped by Button.DOWN"] < 4.1
    assert end_pose(result)[0] > result.trace.poses(0)[0][0] + 30  # 150 mm/s for 3 s


def test_pybricks_light():
    """EV3Brick.light.on(color) and off() (extmod/modbuiltins.c: builtins_ColorLight_on, _Light_off)."""
    result, _ = run_pybricks("light")
    states = [e[3] for e in result.trace.events if e[2] == "leds"]
    both = [(s["led0:red:brick-status"], s["led0:green:brick-status"]) for s in states]
    shown = [pair for i, pair in enumerate(both) if i == 0 or pair != both[i - 1]]
    assert shown == [(0, 0), (0, 255), (255, 255), (255, 0), (0, 0)]  # off, green, orange, red, off
    assert printed(result)[-1].startswith("battery ")


def test_pybricks_screen():
    """EV3Brick.screen draws on the 178 x 128 LCD (bricks/ev3dev/pb_type_ev3dev_image.c)."""
    result, _ = run_pybricks("screen")
    frames = [e[3]["frame"] for e in result.trace.events if e[2] == "lcd"]
    pixels = result.trace.lcd_frames[frames[-1]]
    assert len(pixels) == 178 * 128
    assert pixels.count(0) > 300 and pixels.count(255) > 10000  # black drawing on a white screen
    assert printed(result) == ["screen is 178 x 128"]


def test_pybricks_speaker():
    """beep, play_notes, play_file and say each wait until played (pb_type_ev3dev_speaker.c)."""
    result, _ = run_pybricks("speaker")
    sounds = [e[3] for e in result.trace.events if e[2] == "sound" and e[3]["kind"] != "set_volume"]
    assert [s["kind"] for s in sounds] == ["beep"] * 5 + ["play_file", "speak"]  # 2 beeps, 3 notes
    assert sounds[5]["wav_file"].endswith("communication/hello.wav")
    assert sounds[6]["text"] == "Hello from the simulator"
    assert result.sim_time_s > 0.1 + 0.3 + 2.0 + 1.0  # beeps, the notes at 120 bpm, the file
    assert printed(result) == ["all played"]


def test_pybricks_datalog():
    """StopWatch (extmod/modtools.c) and DataLog (bricks/ev3dev/modules/pybricks/tools.py): the file's
    header, then `time, angle` rows, printed as print(data) shows them."""
    result, _ = run_pybricks("datalog")
    lines = printed(result)
    took = int(lines[0].split()[1])
    assert 1000 <= took < 1100
    log = "\n".join(lines[1:]).strip().splitlines()
    assert log[0] == "time, angle"
    rows = [[int(v) for v in row.split(", ")] for row in log[1:]]
    assert len(rows) == 10
    assert [r[0] for r in rows] == sorted(r[0] for r in rows)
    assert rows[-1][1] > 250  # one turn a second, for most of a second


def test_pybricks_messaging():
    """A server and a client brick exchange a text and a number (bricks/ev3dev/modules/pybricks/
    messaging.py: BluetoothMailboxServer.wait_for_connection, BluetoothMailboxClient.connect,
    TextMailbox, NumericMailbox)."""
    world = load_maze(find_maze("empty"))
    programs = [PYBRICKS / "messaging_server.py", PYBRICKS / "messaging_client.py"]
    result = run_programs(programs, world, time_limit_s=20, hang_after_s=10)
    assert result.status == "finished", result.reason
    said = {(o.robot, o.text) for o in result.trace.output}  # robot 0 runs the server, robot 1 the client
    assert (1, "the server says hello!") in said
    assert (0, "the client says 42.0") in said


def test_pybricks_other_devices():
    """nxtdevices.LightSensor (extmod/modnxtdevices.c), iodevices.Ev3devSensor and DCMotor
    (extmod/modiodevices.c, modmotor.c): on the shipped robot port 1 holds a touch sensor, so the light
    sensor is OSError ENODEV, which the program catches; on the NXT robot file it reads the floor."""
    lines = printed(run_pybricks("other_devices", maze="line")[0])
    assert lines == ["no NXT light sensor on S1", "COL-REFLECT (40,) RGB-RAW 4 values", "arm done"]
    robot = load_robot(EXAMPLES / "robots" / "nxt-light-base.yaml")
    result, _ = run_pybricks("other_devices", maze="line", robot=robot)
    light = printed(result)[0].split()
    assert light[:4] == ["NXT", "light", "sensor:", "reflection"] and 0 <= int(light[4]) <= 100
    assert printed(result)[1:] == lines[1:]
