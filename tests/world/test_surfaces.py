"""A world file calibrates its floor (`surfaces:`): what white, black and each EV3 colour read in
reflected light and RGB-RAW, so a program tuned on a team's own mat behaves in the simulator as on it.

References:
- ev3dev kernel drivers, github.com/ev3dev/lego-linux-drivers (commit 1b387f3),
  sensors/ev3_uart_sensor_defs.c, LEGO_EV3_COLOR: COL-REFLECT "Reflected light - sets LED color to
  red", pct 0-100; RGB-RAW "Raw Color Components - all LEDs rapidly cycling", values 0-1020.
- python-ev3dev2 2.1.0, ev3dev2/sensor/lego.py: ColorSensor.reflected_light_intensity (COL-REFLECT,
  value0), ColorSensor.raw (RGB-RAW, value0..2), ColorSensor.rgb (raw scaled by red_max, green_max,
  blue_max, 300 until calibrate_white()), ColorSensor.color (COL-COLOR).
- A real sensor's readings depend on the surface: LEGO's mats, printed paper and classroom floors
  read differently, which is why teams measure white and black on their own table before a run.
"""

import textwrap

import pytest

from ev3sim2d.simulator.simulation import Simulation
from ev3sim2d.world.cell import Cell
from ev3sim2d.world.maze_file import parse_maze
from ev3sim2d.world.robot_spec import default_robot, parse_robot
from ev3sim2d.world.source_error import WorldFileError
from tests.inline_world import two_wheel_robot

TEAM_TABLE = """\
  white: {reflect: 92, rgb_raw: [250, 250, 240]}
  green: {reflect: 12, rgb_raw: [20, 160, 30]}
  black: {reflect: 4}
"""


def world(surfaces: str = TEAM_TABLE, inner: str = "..........gg..") -> object:
    """A corridor of 4 cm cells, the robot at its left end facing right; `inner` is the floor row it
    drives along (in the legend's characters), between two white rows."""
    width = len(inner) + 2
    rows = ["#" * width, "#" + "." * len(inner) + "#", "#" + inner + "#", "#" + "." * len(inner) + "#"]
    rows.append("#" * width)
    grid = textwrap.indent("\n".join(rows), "  ")
    extra = f"surfaces:\n{surfaces}" if surfaces else ""
    text = (
        f"title: table\ncell_cm: 8\ngrid: |\n{grid}\nstart: {{x_cm: 16, y_cm: 20, heading_deg: 0}}\n{extra}"
    )
    return parse_maze(text, "table.yaml")


def test_a_program_tuned_on_the_teams_table_finds_the_green_patch(run):
    """The team measured its mat: white reads 92 and green's RGB-RAW red is 20.  Their program trusts
    white >= 90 and stops at the first green (red <= 30, green >= 100).  With `surfaces:` saying so,
    the program drives across the white and stops on the green.  Today `surfaces:` is refused, and
    without it white reads 75 and green's red 40: the program gives up at once ("not on white")."""
    result = run(
        """
        from ev3dev2.motor import MoveTank, OUTPUT_B, OUTPUT_C, SpeedPercent
        from ev3dev2.sensor.lego import ColorSensor

        cs = ColorSensor()
        tank = MoveTank(OUTPUT_B, OUTPUT_C)
        white = cs.reflected_light_intensity
        print('white', white)
        if white >= 90:
            tank.on(SpeedPercent(15), SpeedPercent(15))
            while True:
                red, green, blue = cs.raw
                if red <= 30 and green >= 100:
                    break
            tank.off()
            print('edge', red, green)
            tank.on_for_degrees(SpeedPercent(15), SpeedPercent(15), 60)  # 3 cm on, the spot all green
            print('green', *cs.raw, cs.reflected_light_intensity, cs.color_name)
        else:
            print('not on white')
        """,
        world(),
    )
    assert result.status == "finished", result.reason
    white, edge, green = [line.text for line in result.trace.output]
    assert white == "white 92"
    _, red, green_at_edge = edge.split()
    assert int(red) <= 30 and int(green_at_edge) >= 100  # it stopped as the spot came onto the green
    assert green == "green 20 160 30 12 Green"
    x, _, _ = result.trace.poses(0)[-1]
    assert 80 <= x + 7 <= 100  # the colour sensor (7 cm ahead of the centre) is on the green cells


def test_greys_lie_between_the_calibrated_black_and_white(run):
    """A grey of shade s (legend digit d is shade round(d*100/9)) reads black's values blended towards
    white's, s % of the way: with white 92 and black 4, digit 5 (shade 56) reflects 4 + 88 x 0.56 = 53
    and its RGB-RAW lies between black's and white's likewise; the NXT light sensor, 20 + 0.55 x the EV3
    sensor's value, follows.  Today `surfaces:` is refused, and digit 5 reads 44 whatever the world
    says."""
    spec = parse_robot(
        two_wheel_robot(
            "two light sensors",
            "{port: 3, kind: color, angle_deg: 0, radius_cm: 7, facing: down}",
            "{port: 1, kind: nxt-light, angle_deg: 0, radius_cm: 7, facing: down}",
        )
    )
    result = run(
        """
        from ev3dev2.sensor import INPUT_1, INPUT_3
        from ev3dev2.sensor.lego import ColorSensor, LightSensor

        cs = ColorSensor(INPUT_3)
        print('grey', cs.reflected_light_intensity, *cs.raw)
        print('nxt', round(LightSensor(INPUT_1).reflected_light_intensity, 1))
        """,
        world(inner="5555555555555"),
        robot=spec,
    )
    assert result.status == "finished", result.reason
    shade = round(5 * 100 / 9)
    black_rgb, white_rgb = (20.0, 22.0, 18.0), (250.0, 250.0, 240.0)  # black's RGB-RAW is the model's
    rgb = [round(b + (w - b) * shade / 100) for b, w in zip(black_rgb, white_rgb, strict=True)]
    reflect = 4 + 88 * shade / 100
    assert [line.text for line in result.trace.output] == [
        f"grey {round(reflect)} {rgb[0]} {rgb[1]} {rgb[2]}",
        f"nxt {round(20 + 0.55 * reflect, 1)}",
    ]


def test_colours_a_world_does_not_calibrate_read_as_modelled(run):
    """Calibrating white does not change blue: blue reads the modelled 9 and (30, 62, 150).  Today a
    world with `surfaces:` is refused."""
    result = run(
        """
        from ev3dev2.sensor.lego import ColorSensor

        cs = ColorSensor()
        print(cs.reflected_light_intensity, *cs.raw)
        """,
        world(surfaces="  white: {reflect: 92}\n", inner="bbbbbbbbbbbbb"),
    )
    assert result.status == "finished", result.reason
    assert [line.text for line in result.trace.output] == ["9 30 62 150"]


def test_a_cell_changed_during_a_run_reads_as_the_world_calibrates_it():
    """A live run's edit (Simulation.set_cell) paints with the world's surfaces too: a cell made green
    reads the calibrated green.  Today the world is refused."""
    sim = Simulation(world(), [("robot", default_robot(), world().start)])
    sim.set_cell(3, 2, Cell.floor_color("green"))
    assert sim.floor.reflected[2][3] == 12.0
    assert tuple(sim.floor.raw_rgb[2][3]) == (20.0, 160.0, 30.0)
    assert sim.floor.reflected[2][4] == 92.0  # white floor beside it


@pytest.mark.parametrize(
    "surfaces, message",
    [
        ("  white: {reflect: 120}\n", "11:20: 'reflect' is a COL-REFLECT reading, 0 to 100"),
        ("  grey: {reflect: 50}\n", "11:3: unknown colour 'grey' in 'surfaces'"),
        ("  whte: {reflect: 90}\n", "11:3: unknown colour 'whte' in 'surfaces'; did you mean 'white'?"),
        ("  white: {}\n", "11:10: 'white' needs what the sensor reads on it: `reflect` (COL-REFLECT)"),
        ("  white: {rgb: [250, 250, 240]}\n", "11:11: unknown key 'rgb' in 'white'; did you mean 'rgb_raw'?"),
        (
            "  white: {rgb_raw: [250, 250, 2400]}\n",
            "11:20: 'rgb_raw' is an RGB-RAW reading, [red, green, blue]",
        ),
        ("  white: {rgb_raw: [250, 250]}\n", "11:20: 'rgb_raw' must be a list of 3 numbers, got 2 items"),
        ("  black: {reflect: 80}\n", "11:20: white must reflect more than black (white reads 75, black 80)"),
    ],
)
def test_a_mistake_in_the_surfaces_names_the_line_and_the_fix(surfaces, message):
    """docs/world-files.md: every mistake in a world file is reported as `file:line:column: what is
    wrong; what to write instead`.  Today `surfaces` itself is an unknown key."""
    with pytest.raises(WorldFileError) as caught:
        world(surfaces=surfaces)
    assert f"table.yaml:{message}" in str(caught.value)
