"""The renderer's colours, in OpenCV's blue-green-red order.

Marks that must stand out (the ultrasonic beam, its hit point, wall contacts,
the colour sensor's spot, regions) take the Okabe-Ito palette, which stays
distinguishable for viewers with any common colour-vision deficiency; they
differ in lightness as well as hue, and every state also has a word in the panel.
"""

from __future__ import annotations


def bgr(rgb: tuple[int, int, int]) -> tuple[int, int, int]:
    """An (r, g, b) colour as OpenCV wants it."""
    r, g, b = rgb
    return (int(b), int(g), int(r))


# Okabe-Ito, as (r, g, b)
ORANGE = (230, 159, 0)
SKY_BLUE = (86, 180, 233)
BLUISH_GREEN = (0, 158, 115)
YELLOW = (240, 228, 66)
BLUE = (0, 114, 178)
VERMILLION = (213, 94, 0)
REDDISH_PURPLE = (204, 121, 167)

ROBOT_COLORS = [SKY_BLUE, BLUISH_GREEN, REDDISH_PURPLE, YELLOW, BLUE, ORANGE]
"""Colours, in order, for robots that would look like an earlier one (e.g. all from the default robot
file): each takes the first of these that looks like no robot's colour yet."""
ALIKE_DISTANCE = 80.0  # colours closer than this (redmean distance, 0..765) look alike


def looks_alike(a: tuple[int, int, int], b: tuple[int, int, int]) -> bool:
    """Whether two (r, g, b) colours are hard to tell apart: the cheap "redmean" estimate of their distance."""
    r_mean = (a[0] + b[0]) / 2
    dr, dg, db = (a[k] - b[k] for k in range(3))
    distance = ((2 + r_mean / 256) * dr * dr + 4 * dg * dg + (2 + (255 - r_mean) / 256) * db * db) ** 0.5
    return distance < ALIKE_DISTANCE


# the map
SURROUND = bgr((40, 42, 48))  # outside the world
GRID_LINE_DARKEN = 0.90  # floor under a cell line keeps this share of its brightness
WALL_EDGE = bgr((120, 120, 126))
REGION = bgr(BLUE)
BEAM = bgr(SKY_BLUE)
HIT = bgr(VERMILLION)
CONTACT = bgr(VERMILLION)
SPOT = bgr(REDDISH_PURPLE)
OUTLINE = bgr((30, 30, 30))
WHEEL = bgr((45, 45, 45))
SENSOR_BODY = bgr((70, 70, 74))
LABEL_BG = bgr((255, 255, 255))
LABEL_FG = bgr((20, 20, 20))
CAPTION_BG = bgr((20, 20, 24))
CAPTION_FG = bgr((255, 255, 255))

# the panel
PANEL_BG = bgr((30, 32, 38))
PANEL_RULE = bgr((70, 72, 80))
TEXT = bgr((235, 235, 235))
TEXT_DIM = bgr((150, 152, 160))
HEADING = bgr((255, 255, 255))
STDERR = bgr((255, 140, 90))
STATE_COLORS = {
    "running": bgr(BLUISH_GREEN),
    "stalled": bgr(VERMILLION),
    "overloaded": bgr(VERMILLION),
    "holding": bgr(SKY_BLUE),
    "ramping": bgr(YELLOW),
}
STATUS_COLORS = {
    "finished": bgr(BLUISH_GREEN),
    "time_limit": bgr(SKY_BLUE),
    "error": bgr(VERMILLION),
    "hung": bgr(VERMILLION),
    "interrupted": bgr(YELLOW),
}
