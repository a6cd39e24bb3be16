"""Several robots in one world, drawn: each in its own colour with its number, each with its panel section.

Every trace here is a real run of small driving programs in a small arena."""

import dataclasses
import textwrap

import numpy as np
import pytest

from ev3sim2d.render import palette
from ev3sim2d.render.frame import FrameRenderer, draw_world_picture
from ev3sim2d.render.layout import FrameLayout
from ev3sim2d.render.robot_layer import robot_colors, robot_looks
from ev3sim2d.render.timeline import Timeline
from ev3sim2d.simulator.run import run_programs
from ev3sim2d.world.maze_file import parse_maze
from ev3sim2d.world.robot_spec import DEFAULT_ROBOT_COLOR, load_robot, shipped_robots_dir
from tests.inline_world import arena

SIZE = (1280, 720)
DRIVE = """
    from ev3dev2.motor import OUTPUT_B, OUTPUT_C, MoveTank

    MoveTank(OUTPUT_B, OUTPUT_C).on_for_seconds({left}, {right}, 2.0)
    print("done")
"""
# far apart, so that no robot's beam label covers another robot's middle; heading to the world's middle
STARTS = [(40, 40, 0), (40, 200, 0), (200, 40, 180), (200, 200, 180)]


def _run(tmp_path_factory, count: int, robots=None):
    folder = tmp_path_factory.mktemp(f"robots{count}")
    programs = []
    for i in range(count):
        path = folder / f"p{i}.py"
        path.write_text(textwrap.dedent(DRIVE.format(left=20 + 10 * i, right=40)))
        programs.append(path)
    poses = "\n".join(f"  - {{x_cm: {x}, y_cm: {y}, heading_deg: {h}}}" for x, y, h in STARTS[:count])
    world = arena(width=20, height=20, cell_cm=12, start="\n" + poses if count > 1 else poses[4:])
    return run_programs(programs, world, robots, 5.0, 0, 5.0, None).trace


@pytest.fixture(scope="module")
def one_trace(tmp_path_factory):
    return _run(tmp_path_factory, 1)


@pytest.fixture(scope="module")
def two_traces(tmp_path_factory):
    return _run(tmp_path_factory, 2)


@pytest.fixture(scope="module")
def four_trace(tmp_path_factory):
    return _run(tmp_path_factory, 4)


def _at_end(trace):
    renderer = FrameRenderer(trace, SIZE)
    tick = renderer.timeline.tick_at(renderer.timeline.end_s)
    return renderer, renderer.frame_at(renderer.timeline.end_s), tick


def _body_colour(renderer, frame, i, tick) -> np.ndarray:
    """The colour drawn beside robot i's axle, on its body between the arrow and a wheel."""
    x, y, heading = renderer.timeline.pose(i, tick)
    h = np.radians(heading)
    look = renderer.looks[i]
    side = (look.axle_track_cm / 2 - 1.4) / 2 + 0.3  # between the arrow (2.6 cm) and the tyre
    side = max(side, 3.3)
    px, py = renderer.view.px(x - side * np.sin(h) + 2.0 * np.cos(h), y + side * np.cos(h) + 2.0 * np.sin(h))
    return frame[py, px]


def _disc_centre(view, look, pose) -> tuple[int, int]:
    """Where the robot's number goes: the middle of its body behind the heading arrow."""
    x, y, heading = pose
    back = -(look.back_cm + 1.5) / 2
    h = np.radians(heading)
    return view.px(x + back * np.cos(h), y + back * np.sin(h))


def _ink_of(image, view, look, pose, color, r: int = 9) -> int:
    """How many pixels of exactly `color` there are within r px of where the robot's number goes."""
    px, py = _disc_centre(view, look, pose)
    patch = image[py - r : py + r + 1, px - r : px + r + 1]
    yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
    return int((_is(patch, color) & (xx**2 + yy**2 <= r * r)).sum())


def _is(pixels, color) -> np.ndarray:
    """Which pixels are `color`, or if that is "dark", which are nearly black (the digits' ink)."""
    if color == "dark":
        return (pixels < 100).all(axis=2)
    return (pixels == np.array(color, np.uint8)).all(axis=2)


def test_every_robot_is_drawn_in_a_colour_of_its_own(four_trace):
    renderer, frame, tick = _at_end(four_trace)
    colours = [tuple(int(c) for c in _body_colour(renderer, frame, i, tick)) for i in range(4)]
    assert colours == [look.color for look in renderer.looks]
    assert len(set(colours)) == 4
    # the first keeps the robot file's colour; the others take the palette's, in order
    assert colours[0] == palette.bgr(DEFAULT_ROBOT_COLOR)
    assert colours[1:] == [palette.bgr(c) for c in palette.ROBOT_COLORS[:3]]
    rgb = [tuple(reversed(c)) for c in colours]
    assert not any(palette.looks_alike(a, b) for k, a in enumerate(rgb) for b in rgb[k + 1 :])


def test_trails_take_each_robots_colour(two_traces):
    renderer, frame, tick = _at_end(two_traces)
    for i, look in enumerate(renderer.looks):
        path = two_traces.poses(i)
        x, y = path[len(path) // 10, :2]  # early on, well behind where the robot is now
        assert np.hypot(*(path[-1, :2] - (x, y))) > 15
        px, py = renderer.view.px(x, y)
        patch = frame[py - 1 : py + 2, px - 1 : px + 2].reshape(-1, 3).astype(int)
        # the trail fades from its tint of the robot's colour (white and the colour) into the colour
        low = np.minimum(look.trail_color, look.color) - 2
        high = np.maximum(look.trail_color, look.color) + 2
        inside = ((patch >= low) & (patch <= high)).all(axis=1)
        assert inside.any(), (i, patch.tolist(), look.trail_color, look.color)
        # and is nothing like the other robot's
        other = renderer.looks[1 - i]
        assert not np.isin(patch, other.color).all(axis=1).any()


def test_a_robots_own_colour_is_kept_and_a_look_alike_one_is_changed():
    default, red = DEFAULT_ROBOT_COLOR, (200, 30, 30)
    assert robot_colors([default, red]) == [default, red]
    # the second is too like the first (the palette's orange); the third keeps its own, the fourth must not
    # take a colour like the third's
    colors = robot_colors([default, (230, 159, 0), palette.SKY_BLUE, default])
    assert colors[0] == default and colors[2] == palette.SKY_BLUE
    assert len({*colors}) == 4
    assert not any(palette.looks_alike(a, b) for k, a in enumerate(colors) for b in colors[k + 1 :])
    assert robot_colors([default] * 3) == robot_colors([default] * 3)  # the same every time


def test_robots_from_robot_files_of_their_own_colours_keep_them(tmp_path_factory):
    base = load_robot(shipped_robots_dir() / "ev3-driving-base.yaml")
    red = dataclasses.replace(base, color=(200, 30, 30))
    trace = _run(tmp_path_factory, 2, [red, base])
    renderer, frame, tick = _at_end(trace)
    assert tuple(_body_colour(renderer, frame, 0, tick)) == palette.bgr((200, 30, 30))
    assert tuple(_body_colour(renderer, frame, 1, tick)) == palette.bgr(DEFAULT_ROBOT_COLOR)


def test_each_robot_carries_its_number_upright(four_trace):
    renderer, frame, tick = _at_end(four_trace)
    assert renderer.numbers == [1, 2, 3, 4]
    for i, look in enumerate(renderer.looks):
        # the white disc and the dark digits on it
        pose = renderer.timeline.pose(i, tick)
        assert _ink_of(frame, renderer.view, look, pose, palette.LABEL_BG) > 100
        assert _ink_of(frame, renderer.view, look, pose, "dark", r=8) > 15
    # the digits are the same pixels whichever way the robot faces: robots 3 and 4 face the other way
    # from robots 1 and 2 (and turned by different amounts), yet a "1" drawn is a "1"
    renderer.numbers = [1, 1, 1, 1]
    frame = renderer.frame_at(renderer.timeline.end_s)
    digits = []
    for i, look in enumerate(renderer.looks):
        px, py = _disc_centre(renderer.view, look, renderer.timeline.pose(i, tick))
        r = 7  # (well inside the disc's outline)
        patch = frame[py - r : py + r + 1, px - r : px + r + 1]
        yy, xx = np.mgrid[-r : r + 1, -r : r + 1]
        ink = _is(patch, "dark") & (xx**2 + yy**2 <= r * r)
        ys, xs = np.nonzero(ink)
        digits.append(ink[ys.min() : ys.max() + 1, xs.min() : xs.max() + 1])
    assert all(d.shape == digits[0].shape and (d == digits[0]).all() for d in digits)


def test_a_single_robot_has_no_number_and_its_robot_files_colour(one_trace):
    renderer, frame, tick = _at_end(one_trace)
    assert renderer.numbers == [None]
    assert tuple(_body_colour(renderer, frame, 0, tick)) == palette.bgr(DEFAULT_ROBOT_COLOR)
    pose = renderer.timeline.pose(0, tick)
    assert _ink_of(frame, renderer.view, renderer.looks[0], pose, palette.LABEL_BG, r=6) == 0  # no disc
    assert _ink_of(frame, renderer.view, renderer.looks[0], pose, palette.LABEL_FG) == 0  # no digits
    panel = renderer.panel
    assert not panel.compact and panel.font.size_px == renderer.layout.font_px


def test_the_panel_has_a_section_per_robot_headed_by_its_number(two_traces):
    renderer, frame, _ = _at_end(two_traces)
    panel = renderer.panel
    assert len(panel.sections) == len(panel.robot_headers) == 2
    assert not panel.compact  # two robots fit at full size
    for i, ((top, bottom), header) in enumerate(zip(panel.sections, panel.robot_headers, strict=True)):
        assert top == header and bottom <= renderer.layout.height
        # the header's swatch is the robot's colour
        row = frame[header : header + panel.row, panel.x0 : panel.x1]
        assert (row == np.array(renderer.looks[i].color, np.uint8)).all(axis=2).sum() > 20
    assert panel.sections[0][1] < panel.sections[1][0]


def test_four_robots_fit_the_panel_at_1280x720(four_trace):
    renderer, frame, _ = _at_end(four_trace)
    panel = renderer.panel
    assert len(panel.sections) == 4
    height = renderer.layout.height
    for k, (top, bottom) in enumerate(panel.sections):
        assert 0 <= top < bottom <= height
        if k:
            assert panel.sections[k - 1][1] <= top
        rows = panel.robot_rows[k]
        assert all(y + panel.font.height <= height for y in rows.sensor_ys + rows.motor_ys)
        assert len(rows.sensor_ys) == len(four_trace.robots[k]["sensors"])
        assert len(rows.motor_ys) == len(four_trace.robots[k]["motors"])
    assert panel.printed_rows >= 2  # and room is left for what they print
    assert panel.font.size_px >= 9
    for i, header in enumerate(panel.robot_headers):
        row = frame[header : header + panel.row, panel.x0 : panel.x1]
        assert (row == np.array(renderer.looks[i].color, np.uint8)).all(axis=2).sum() > 10


def test_the_world_picture_numbers_several_robots(two_traces, one_trace):
    for trace, numbered in ((two_traces, True), (one_trace, False)):
        image = draw_world_picture(trace, 800)
        world = parse_maze(trace.world["text"], "<trace>")
        view = FrameLayout.picture(world.grid.size_cm, 800, caption_lines=2).view
        timeline = Timeline(trace)
        for i, look in enumerate(robot_looks(trace.robots)):
            digits = _ink_of(image, view, look, timeline.pose(i, -1), palette.LABEL_FG)
            assert (digits > 5) == numbered, (i, digits)
