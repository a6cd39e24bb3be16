"""Frames of a run, drawn from its trace alone: the world, the robots and what they sense, and the panel.

The still world (and the panel's headings) is drawn once into a background;
trails grow on a copy of it as time moves on; each frame copies that and
draws only what moves: the recent trail, beams, robots, contact bursts,
captions and the panel's values.
"""

from __future__ import annotations

from bisect import bisect_right
from pathlib import Path

import cv2
import numpy as np

from ..results.output_files import writing
from ..results.trace import Trace
from ..world.cell import Cell
from ..world.maze_file import parse_maze
from ..world.world import World
from . import palette
from .layout import DEFAULT_SIZE, FrameLayout
from .panel import Panel
from .robot_layer import (
    TRAIL_RECENT_S,
    beam_distance_cm,
    contact_point,
    draw_beam,
    draw_contact,
    draw_recent_trail,
    draw_robot,
    draw_trail,
    robot_looks,
)
from .text import Font, draw_label, draw_text
from .timeline import Timeline
from .walls import Walls
from .world_layer import draw_world

CAPTION_MIN_S = 1.5  # speech captions stay at least this long in the video


def world_of(trace: Trace) -> World:
    """The trace's world, as drawn: read from the text the trace holds, without its robot files (the
    trace holds its robots; the world file's folder may be far away, or on another computer)."""
    return parse_maze(trace.world["text"], trace.world.get("name") or "<trace>", robots=False)


class FrameRenderer:
    """Draws the frame at any simulated time t; fastest when t only moves forward."""

    def __init__(self, trace: Trace, size: tuple[int, int] = DEFAULT_SIZE, speed: float = 1.0) -> None:
        self.trace = trace
        self.speed = speed
        self.timeline = Timeline(trace)
        self.world = world_of(trace)
        self.layout = FrameLayout.video(self.world.grid.size_cm, *size)
        self.view = self.layout.view
        self.looks = robot_looks(trace.robots)
        # with several robots each carries its number (robot1 is 1), as in the panel's headings
        self.numbers = [i + 1 if len(self.looks) > 1 else None for i in range(len(self.looks))]
        self.walls = Walls(self.world.grid.wall_rectangles())
        self.label_font = Font(max(8, int(round(self.layout.font_px * 0.85))))
        self.trail_px = max(1, self.view.length(0.6))
        self.map_bounds = (0, 0, self.layout.panel_x, self.layout.height)
        self.panel = Panel(trace, self.timeline, self.looks, self.layout, speed)
        self.caption_font = Font(self.layout.font_px, bold=True)  # (the panel's may be smaller)
        # a live run's hand in the world (ev3sim2d/live): cells changed, robots put elsewhere
        self._cell_events = sorted((e[0], e[3]) for e in trace.events if e[2] == "cell")
        self._cells_shown = 0
        self._placed: dict[int, list[int]] = {}  # robot -> ticks after which it was put elsewhere
        for t, robot, kind, _ in trace.events:
            if kind == "place":
                self._placed.setdefault(robot, []).append(self.timeline.tick_at(t))
        self._draw_background()

    def _draw_background(self) -> None:
        background = np.empty((self.layout.height, self.layout.width, 3), dtype=np.uint8)
        background[:] = palette.SURROUND
        draw_world(background, self.world, self.view, self.label_font)
        self.panel.draw_base(background)
        self.background = background
        self._reset_trails()

    def _show_cells_at(self, t_s: float) -> None:
        """The world as a live run's hand had changed it by t_s: drawn again when that changes."""
        count = bisect_right([t for t, _ in self._cell_events], t_s)
        if count == self._cells_shown:
            return
        world = world_of(self.trace)
        grid = world.grid
        for _, cell in self._cell_events[:count]:
            grid = grid.with_cell(cell["col"], cell["row"], Cell(cell["wall"], cell["shade"], cell["color"]))
        world.grid = grid
        self.world = world
        self.walls = Walls(grid.wall_rectangles())
        self._cells_shown = count
        self._draw_background()

    def _pieces(self, robot: int, first: int, last: int) -> list[tuple[int, int]]:
        """Ticks first..last cut where the robot was put elsewhere: a trail does not join the jump."""
        pieces, start = [], first
        for placed in self._placed.get(robot, ()):
            if start <= placed < last:
                pieces.append((start, placed))
                start = placed + 1
        pieces.append((start, last))
        return pieces

    def _reset_trails(self) -> None:
        self._canvas = self.background.copy()
        self._trail_tick = [-1] * len(self.looks)

    def _grow_trails(self, tick: int) -> None:
        """Draw the old part of each path (and the marks of past contacts) onto the canvas, up to `tick`."""
        if any(done > tick for done in self._trail_tick):
            self._reset_trails()
        tl = self.timeline
        for i, look in enumerate(self.looks):
            done = self._trail_tick[i]
            if tick <= done:
                continue
            for a, b in self._pieces(i, done, tick):
                draw_trail(self._canvas, self.view, tl.path(i, a, b), look.trail_color, self.trail_px)
            for contact in tl.contact_ticks(i):
                if done < contact <= tick:
                    point = contact_point(look, tl.pose(i, int(contact)), self.walls)
                    if point is not None:
                        draw_contact(self._canvas, self.view, point, active=False)
            self._trail_tick[i] = tick

    def frame_at(self, t_s: float, out: np.ndarray | None = None) -> np.ndarray:
        """The frame showing simulated time t_s (BGR, height × width × 3), drawn into `out` if given."""
        tl = self.timeline
        tick = tl.tick_at(t_s)
        if self._cell_events:
            self._show_cells_at(t_s)
        recent_ticks = int(round(TRAIL_RECENT_S / max(self.trace.tick_s, 1e-6)))
        self._grow_trails(max(tick - recent_ticks, -1))
        if out is None:
            frame = self._canvas.copy()
        else:
            frame = out
            np.copyto(frame, self._canvas)
        for i, look in enumerate(self.looks):
            for a, b in self._pieces(i, max(self._trail_tick[i], -1), tick):
                draw_recent_trail(frame, self.view, look, tl.path(i, a, b), self.trail_px + 1)
        poses, pressed_by_robot = [], []
        for i, look in enumerate(self.looks):  # every beam first, so that no label hides a robot
            pose = tl.pose(i, tick)
            pressed = {}
            for sensor in look.sensors:
                reading = tl.sensor(i, sensor.port, t_s)
                distance = beam_distance_cm(sensor, reading)
                if distance is not None:
                    draw_beam(
                        frame, self.view, self.label_font, sensor, pose, distance, self.walls, self.map_bounds
                    )
                if sensor.kind == "touch" and reading is not None and reading[1]:
                    pressed[sensor.port] = bool(reading[1][0])
            poses.append(pose)
            pressed_by_robot.append(pressed)
        for i, (look, pose, pressed) in enumerate(zip(self.looks, poses, pressed_by_robot, strict=True)):
            touching = tl.touching(i, tick)
            draw_robot(frame, self.view, look, pose, pressed, touching, self.numbers[i])
            if touching:
                point = contact_point(look, pose, self.walls)
                if point is not None:
                    draw_contact(frame, self.view, point, active=True)
        self._draw_captions(frame, t_s)
        self.panel.draw(frame, t_s, tick)
        return frame

    def _draw_captions(self, frame: np.ndarray, t_s: float) -> None:
        """What the robots say (and which sound files they play), at the bottom of the map."""
        lines = []
        hold = CAPTION_MIN_S * self.speed
        for s in self.timeline.sounds:
            if s.kind != "tone" and s.start_s <= t_s < max(s.end_s, s.start_s + hold):
                who = self.looks[s.robot].name if len(self.looks) > 1 else "robot"
                lines.append(f"{who} says “{s.text}”" if s.kind == "speech" else f"{who} plays {s.text}")
        font = self.caption_font
        y = self.layout.height - (font.height + 10) * len(lines) - 8
        for line in lines:
            text = font.fit(line, self.layout.panel_x - 40)
            x = (self.layout.panel_x - font.width(text)) // 2 - 6
            draw_label(frame, font, text, x, y, palette.CAPTION_FG, palette.CAPTION_BG, pad=5)
            y += font.height + 10


def draw_final_frame(trace: Trace, size: tuple[int, int] = DEFAULT_SIZE) -> np.ndarray:
    """The frame at the end of the run."""
    renderer = FrameRenderer(trace, size)
    return renderer.frame_at(renderer.timeline.end_s)


def write_png(trace: Trace, path: str | Path, size: tuple[int, int] = DEFAULT_SIZE) -> None:
    """A PNG of the end of the run (`run --png`)."""
    save_png(draw_final_frame(trace, size), path)


def save_png(image: np.ndarray, path: str | Path) -> None:
    with writing(path) as temporary:
        if not cv2.imwrite(str(temporary), image, [cv2.IMWRITE_PNG_COMPRESSION, 3]):
            raise OSError(f"could not write {path}")


def draw_world_picture(trace: Trace, width_px: int = 800) -> np.ndarray:
    """The world with every robot at its start, and a caption: for previews and documentation (`show`)."""
    world = world_of(trace)
    grid = world.grid
    layout = FrameLayout.picture(grid.size_cm, width_px, caption_lines=2)
    image = np.empty((layout.height, layout.width, 3), dtype=np.uint8)
    image[:] = palette.SURROUND
    font = Font(layout.font_px)
    label_font = Font(max(8, int(round(layout.font_px * 0.85))))
    draw_world(image, world, layout.view, label_font)
    timeline = Timeline(trace)
    looks = robot_looks(trace.robots)
    for i, look in enumerate(looks):
        draw_robot(image, layout.view, look, timeline.pose(i, -1), number=i + 1 if len(looks) > 1 else None)
    width_cm, height_cm = grid.size_cm
    y = layout.view.box[3] + max(2, layout.font_px // 2)
    bold = Font(layout.font_px, bold=True)
    draw_text(
        image,
        bold,
        bold.fit(world.title, layout.width - 8),
        8,
        y,
        palette.HEADING,
        background=palette.SURROUND,
    )
    y += int(layout.font_px * 1.45)
    facts = f"{width_cm:g} × {height_cm:g} cm, {grid.width} × {grid.height} cells of {grid.cell_cm:g} cm"
    if world.regions:
        facts += "; regions: " + ", ".join(world.regions)
    draw_text(
        image, font, font.fit(facts, layout.width - 16), 8, y, palette.TEXT_DIM, background=palette.SURROUND
    )
    return image
