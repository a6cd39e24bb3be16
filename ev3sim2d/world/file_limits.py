"""How big a world or robot file may be, and the range of every number in one, in one place.

World and robot files are swapped between students, so each is read as if hostile: these limits are
checked where a file is read (yaml_source.py while the YAML is composed, before anything is built from
it; maze_reader.py and robot_spec.py key by key), and a value outside them is a WorldFileError naming
the file, the line, the range and why.  docs/world-files.md lists them all ("Limits"); the editor's and
the live page's requests are held to the same ones (world_json.py, robot_spec.py).

The ranges are those of real LEGO parts with a wide margin, so that no file a student could mean is
refused while a number that would only break the physics (a 1e12 cm wheel, a 1e-9 cm axle) is.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class DocumentLimits:
    """What one YAML document may hold: its size in characters, its nodes and its depth.

    `nodes` and `chars` count the document as its aliases expand (an alias counts every time it is used),
    so a small file of anchors that stands for a huge one is refused while it is read."""

    kind: str
    chars: int
    nodes: int
    depth: int


# -- sizes --------------------------------------------------------------------------------------------------

WORLD_FILE = DocumentLimits("world file", chars=1_000_000, nodes=100_000, depth=32)
"""A world (or lesson) file: 1 MB is 25 times the largest 200x200 grid with room for comments; 100,000
nodes (each value in the file, aliases expanded) hold regions of every cell of such a grid twice over;
no world needs more than 6 levels of nesting."""
ROBOT_FILE = DocumentLimits("robot file", chars=256_000, nodes=5_000, depth=32)
"""A robot file: 4 motors and 4 sensors of about 10 keys each fill 2 KB; 256 KB leaves comments room."""

MAX_CELLS_PER_SIDE = 200
"""A grid is at most 200 cells each way (the editor's limit): 40,000 cells, 20 m at 10 cm cells."""
MIN_CELLS_PER_SIDE = 3
"""A wall all round and floor inside."""
MAX_STARTS = 8
"""Starts (robots) in one world: a sumo ring of 4 and a convoy of 3 fit; 8 bricks fill a classroom PC."""
MAX_REGIONS = 100
MAX_RECTS_PER_REGION = 500
MAX_REGION_CELLS = MAX_CELLS_PER_SIDE * MAX_CELLS_PER_SIDE
"""`cells:` of one region: no more than the grid's cells."""
MAX_LEGEND_ENTRIES = 100
"""Characters a world's `legend:` adds or changes (the default legend has 19)."""
MAX_BUTTON_PRESSES = 1_000
MAX_BUTTON_TIME_S = 86_400.0
"""A scripted press happens within a day of virtual time (a run is minutes)."""
MAX_MOTORS = 4
MAX_SENSORS = 4
"""The EV3 brick has output ports A-D and input ports 1-4."""

MAX_TITLE_CHARS = 200
MAX_DESCRIPTION_CHARS = 5_000
MAX_NAME_CHARS = 60
"""A robot's name and a region's name (the editor's region-name limit)."""
MAX_PATH_CHARS = 1_000
"""A robot file named in a world file."""

# -- numbers ------------------------------------------------------------------------------------------------

CELL_CM = (1.0, 1000.0)
"""A grid cell's size: the shipped worlds use 2 to 20 cm; the editor page allows up to 1000 cm; under
1 cm a cell is finer than the colour sensor's spot (about 1 cm across)."""

WHEEL_DIAMETER_MM = (20.0, 200.0)
"""LEGO tyres are named by their size in mm, diameter x width: from about 24 x 14 to over 100 mm
across (e.g. 81.6 x 15, 94.3 x 38); the EV3 Education driving base's is 56 x 28 (the shipped robots)."""
AXLE_TRACK_MM = (50.0, 500.0)
"""Two EV3 large motors side by side with their wheels are at least about 6 cm apart wheel to wheel; the
Education driving base is 120 mm; 50 cm is the widest a robot may be in most leagues (WRO, FLL)."""
BODY_REACH_CM = 50.0
"""front_cm, back_cm (each -50..50) and width_cm (up to 50): robot leagues hold robots within
25 to 50 cm a side (WRO 25 x 25 x 25 cm; FLL within 30 cm tall and the launch area)."""
BODY_MIN_CM = 1.0
"""A body at least 1 cm long and wide: the EV3 brick alone is 11 x 8 cm."""
SENSOR_REACH_PAST_BODY_CM = 20.0
"""A sensor sits within 20 cm past the body's farthest corner (a sensor on a boom: two 15-hole beams
reach 24 cm from the brick, partly over the body)."""
ANGLE_DEG = (-360.0, 360.0)
"""angle_deg, aim_deg and a start's heading_deg: one turn either way (any direction can be written)."""
NOISE = (0.0, 100.0)
"""A sensor's noise, a standard deviation in its own unit: 100 is the whole scale of a colour or
infrared reading and 40 % of the ultrasonic sensor's 255 cm."""
LIMITS_DEG = 36_000.0
"""A motor's end stops within 100 turns either way (a winch or a lift; an arm turns less than one)."""

SENSOR_OPTION_RANGES: dict[str, tuple[float, float]] = {
    "spot_cm": (0.1, 10.0),
    # the EV3 colour sensor works best about 1 cm above the floor and sees a spot of about that size;
    # the shipped robots use 1.5
    "bumper_cm": (0.5, BODY_REACH_CM),
    # the touch sensor's own tip is 1 cm wide; a bumper beam across a robot is up to its width
    "cone_deg": (1.0, 180.0),
    # a sound or infrared beam opens some tens of degrees (devices/ultrasonic.py, infrared.py give
    # their defaults); 180 is everything in front
    "max_cm": (1.0, 1000.0),
    # the EV3 ultrasonic sensor measures up to 255 cm, the infrared sensor's proximity 100 is about 70 cm
    # (ev3dev's sensor data: US-DIST-CM reads 0..2550 tenths of a cm; IR-PROX "100% is approximately 70cm")
}
"""Options of the shipped sensor kinds.  An option of a kind of one's own (docs/devices.md) is held to
the range of its unit: OPTION_UNIT_RANGES."""
OPTION_UNIT_RANGES: dict[str, tuple[float, float]] = {
    "cm": (0.01, 1000.0),
    "degrees": (0.01, 360.0),
}
OTHER_OPTION_RANGE = (1e-6, 1e6)
"""An option in another unit: more than 0, and at most a million."""


def sensor_option_range(name: str, unit: str) -> tuple[float, float]:
    """The range of a sensor option, by its name, else by its unit."""
    return SENSOR_OPTION_RANGES.get(name) or OPTION_UNIT_RANGES.get(unit) or OTHER_OPTION_RANGE


def within(value: float, bounds: tuple[float, float]) -> bool:
    """Whether `value` lies in the closed range `bounds` (NaN never does)."""
    low, high = bounds
    return low <= value <= high
