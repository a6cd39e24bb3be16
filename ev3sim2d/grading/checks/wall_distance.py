"""`wall_distance`: at the end of the run, the wall straight ahead is at a given distance."""

from __future__ import annotations

import math

from ..check import Check, Outcome, Param, register
from ..run_record import RunRecord, seconds
from ..world_geometry import distance_to_wall


@register
class WallDistance(Check):
    """Measured at the end, straight ahead from the ultrasonic sensor (or the robot's front) to the
    nearest wall cell; passes when it is between `min_cm` and `max_cm`."""

    KIND = "wall_distance"
    SUMMARY = "at the end, the wall straight ahead of the ultrasonic sensor (or the front) is at a distance"
    PARAMS = (
        Param("min_cm", "cm", "the smallest distance that passes"),
        Param("max_cm", "cm", "the largest distance that passes"),
        Param(
            "from",
            "choice",
            "measure from the ultrasonic sensor, or from the middle of the robot's front",
            default="ultrasonic",
            choices=("ultrasonic", "front"),
        ),
    )

    def hidden_words(self, passed: bool) -> str:
        """What a hidden variant's result says: one sentence for every run that passes, one for every run
        that fails (scoring.py), so that it tells no more than pass or fail."""
        return ("ended" if passed else "did not end") + " at the right distance from the wall ahead"

    def evaluate(self, run: RunRecord) -> Outcome:
        x, y, heading = (float(v) for v in run.poses[-1])
        spec = run.world.robot
        origin = getattr(self, "from")
        forward, left, aim = spec.body.front_cm, 0.0, 0.0
        what = "the robot's front"
        if origin == "ultrasonic":
            sensor = next((s for s in spec.sensors if s.kind == "ultrasonic"), None)
            if sensor is not None:
                (forward, left), aim, what = sensor.offset_cm, sensor.aim_deg, "the ultrasonic sensor"
        h = math.radians(heading)
        sx = x + forward * math.cos(h) - left * math.sin(h)
        sy = y + forward * math.sin(h) + left * math.cos(h)
        distance = distance_to_wall(run.world.grid, sx, sy, heading + aim)
        end = run.end_s
        wanted = f"{self.min_cm:g} to {self.max_cm:g} cm"
        if self.min_cm - 1e-9 <= distance <= self.max_cm + 1e-9:
            return Outcome(
                True,
                f"ended with {what} {distance:.1f} cm from the wall ahead ({wanted} passes)",
                end,
                f"ended with {what} at the right distance from the wall ahead",
            )
        side = "too close to" if distance < self.min_cm else "too far from"
        return Outcome(
            False,
            f"ended at {seconds(end)} {side} the wall: {what} was {distance:.1f} cm from it, not {wanted}",
            end,
            f"ended with {what} {side} the wall ahead",
        )
