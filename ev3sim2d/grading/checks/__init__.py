"""The built-in check kinds, one module each; importing this package registers them all."""

from . import (  # noqa: F401 - each module registers its kind
    avoid_region,
    checkpoints,
    end_heading,
    end_near,
    finished,
    lap,
    on_line,
    reach_region,
    robot_contacts,
    stop_in_region,
    stopped,
    wall_contacts,
    wall_distance,
)
